// fp_add_sub: IEEE-754 single-precision addition and subtraction,
// y = sub ? a - b : a + b.
//
// The pipeline's adders (hwmodel operator `add_sub`, ALTFP_ADD_SUB in the thesis). One
// module with a `sub` input, like ALTFP_ADD_SUB's add_sub port: subtracting is adding
// b with its sign flipped.
//
// Floating-point policy (shared by every arithmetic operator of this library and by
// its Rust reference `rtl::float_policy`, which is the normative text):
//   * a subnormal input is read as a zero of the same sign (the ALTFP cores flush
//     denormals too);
//   * the exact result is rounded to nearest, ties to even, to 24 significant bits
//     with an unbounded exponent range; if the rounded magnitude is below 2^-126 the
//     result is a zero with the exact result's sign, if it is 2^128 or more an
//     infinity: no result is ever subnormal;
//   * exact zeros follow IEEE 754: x - x = +0, (-0) + (-0) = -0;
//   * every NaN result (a NaN input, inf - inf) is the quiet NaN 0x7FC00000.
//
// Datapath: the operand of larger magnitude is kept, the other aligned to it with
// three extra bits (guard, round, and a sticky bit jammed into the lowest bit), then
// added or subtracted; a sum carry shifts right by one, a difference is normalised by
// a leading-zero count. Jamming keeps the rounding exact: the sticky bit is non-zero
// only for exponent differences of 4 or more, where a difference loses at most one
// leading bit. A combinational core followed by a LATENCY-deep register pipeline
// (fp_delay).
//
// Verilog-2005, synthesizable; part of the rtprof `rtl` crate.
module fp_add_sub #(
    parameter LATENCY = 7
) (
    input clk,
    input [31:0] a,
    input [31:0] b,
    input sub,
    output [31:0] y
);
    reg [31:0] r;

    reg sa, sb, a_zero, b_zero, a_inf, b_inf, a_nan, b_nan;
    reg [7:0] ea, eb;
    reg [22:0] fa, fb;
    reg swap, eff_sub, s_big, found, g, st, up;
    reg [7:0] e_big, e_small, d;
    reg [23:0] m_big, m_small;
    reg [26:0] x_small, x_sh, mask, m;
    reg [27:0] sum;
    reg [4:0] lz;
    // mr[23] is the hidden one: it is not stored.
    /* verilator lint_off UNUSEDSIGNAL */
    reg [24:0] mr;
    /* verilator lint_on UNUSEDSIGNAL */
    integer e, i;

    always @* begin
        sa = a[31];
        ea = a[30:23];
        fa = a[22:0];
        sb = b[31] ^ sub;
        eb = b[30:23];
        fb = b[22:0];
        a_zero = (ea == 8'd0);
        b_zero = (eb == 8'd0);
        a_inf = (ea == 8'hFF) && (fa == 23'd0);
        b_inf = (eb == 8'hFF) && (fb == 23'd0);
        a_nan = (ea == 8'hFF) && (fa != 23'd0);
        b_nan = (eb == 8'hFF) && (fb != 23'd0);

        // Defaults (no latches): the finite path's intermediates.
        swap = ({eb, fb} > {ea, fa});
        s_big = swap ? sb : sa;
        e_big = swap ? eb : ea;
        e_small = swap ? ea : eb;
        m_big = swap ? {1'b1, fb} : {1'b1, fa};
        m_small = swap ? {1'b1, fa} : {1'b1, fb};
        eff_sub = sa ^ sb;
        d = e_big - e_small;

        // Align the smaller operand; bits shifted out are jammed into bit 0.
        x_small = {m_small, 3'b000};
        x_sh = x_small >> d;
        mask = (27'd1 << d) - 27'd1;
        if (d >= 8'd27) begin
            x_sh = 27'd0;
            mask = {27{1'b1}};
        end
        x_sh[0] = x_sh[0] | (|(x_small & mask));

        lz = 5'd0;
        if (eff_sub) begin
            sum = {1'b0, m_big, 3'b000} - {1'b0, x_sh};
            found = 1'b0;
            for (i = 26; i >= 0; i = i - 1) begin
                if (!found) begin
                    if (sum[i]) found = 1'b1;
                    else lz = lz + 5'd1;
                end
            end
            m = sum[26:0] << lz;
            e = {24'd0, e_big} - {27'd0, lz};
        end else begin
            sum = {1'b0, m_big, 3'b000} + {1'b0, x_sh};
            found = 1'b0;
            if (sum[27]) begin
                m = {sum[27:2], sum[1] | sum[0]};
                e = {24'd0, e_big} + 1;
            end else begin
                m = sum[26:0];
                e = {24'd0, e_big};
            end
        end

        // Round to nearest even at bit 3 (m[26] is the hidden one).
        g = m[2];
        st = m[1] | m[0];
        up = g & (st | m[3]);
        mr = {1'b0, m[26:3]} + {24'd0, up};
        if (mr[24]) begin
            mr = {2'b01, 23'd0};
            e = e + 1;
        end

        if (a_nan || b_nan || (a_inf && b_inf && (sa != sb)))
            r = 32'h7FC0_0000;
        else if (a_inf)
            r = {sa, 8'hFF, 23'd0};
        else if (b_inf)
            r = {sb, 8'hFF, 23'd0};
        else if (a_zero && b_zero)
            r = {sa & sb, 31'd0};
        else if (b_zero)
            r = {sa, ea, fa};
        else if (a_zero)
            r = {sb, eb, fb};
        else if (sum == 28'd0)
            r = 32'd0;  // exact cancellation: +0 when rounding to nearest
        else if (e >= 255)
            r = {s_big, 8'hFF, 23'd0};
        else if (e <= 0)
            r = {s_big, 31'd0};  // below the smallest normal after rounding: flush
        else
            r = {s_big, e[7:0], mr[22:0]};
    end

    fp_delay #(.WIDTH(32), .LATENCY(LATENCY)) delay (.clk(clk), .d(r), .q(y));
endmodule
