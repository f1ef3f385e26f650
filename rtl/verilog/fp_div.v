// fp_div: IEEE-754 single-precision division, y = a / b.
//
// The pipeline's divider (hwmodel operator `divide`, ALTFP_DIV in the thesis).
//
// Floating-point policy (shared by every arithmetic operator of this library and by
// its Rust reference `rtl::float_policy`, which is the normative text):
//   * a subnormal input is read as a zero of the same sign (the ALTFP cores flush
//     denormals too);
//   * the exact result is rounded to nearest, ties to even, to 24 significant bits
//     with an unbounded exponent range; if the rounded magnitude is below 2^-126 the
//     result is a zero with the exact result's sign, if it is 2^128 or more an
//     infinity: no result is ever subnormal;
//   * x / 0 is an infinity and 0 / x, x / inf a zero, signed by the XOR of the signs
//     (a subnormal divisor is a zero divisor);
//   * every NaN result (a NaN input, 0 / 0, inf / inf) is the quiet NaN 0x7FC00000.
//
// Datapath: a restoring radix-2 digit recurrence, written as a `for` loop in the
// combinational core (no `/` operator): 26 quotient bits (24 significand bits and a
// guard bit after pre-normalising the dividend so that the first bit is one) and a
// sticky bit from the final remainder. A quotient of two 24-bit significands is never
// exactly halfway between two floats, so ties cannot occur, but the rounding is the
// general one. A combinational core followed by a LATENCY-deep register pipeline
// (fp_delay); the recurrence is deep logic, meant to be spread over the registers by
// retiming.
//
// Verilog-2005, synthesizable; part of the rtprof `rtl` crate.
module fp_div #(
    parameter LATENCY = 6
) (
    input clk,
    input [31:0] a,
    input [31:0] b,
    output [31:0] y
);
    reg [31:0] r;

    reg s, a_zero, b_zero, a_inf, b_inf, a_nan, b_nan, g, st, up;
    reg [7:0] ea, eb;
    reg [22:0] fa, fb;
    reg [23:0] ma, mb, m;
    reg [25:0] rem, q;
    reg [26:0] diff;
    // mr[23] is the hidden one: it is not stored.
    /* verilator lint_off UNUSEDSIGNAL */
    reg [24:0] mr;
    /* verilator lint_on UNUSEDSIGNAL */
    integer e, i;

    always @* begin
        s = a[31] ^ b[31];
        ea = a[30:23];
        eb = b[30:23];
        fa = a[22:0];
        fb = b[22:0];
        a_zero = (ea == 8'd0);
        b_zero = (eb == 8'd0);
        a_inf = (ea == 8'hFF) && (fa == 23'd0);
        b_inf = (eb == 8'hFF) && (fb == 23'd0);
        a_nan = (ea == 8'hFF) && (fa != 23'd0);
        b_nan = (eb == 8'hFF) && (fb != 23'd0);

        ma = {1'b1, fa};
        mb = {1'b1, fb};
        // Pre-normalise: the partial remainder starts in [mb, 2 mb), so the first
        // quotient bit is one and q has its leading one at bit 25.
        if (ma < mb) begin
            rem = {1'b0, ma, 1'b0};
            e = {24'd0, ea} - {24'd0, eb} + 126;
        end else begin
            rem = {2'b00, ma};
            e = {24'd0, ea} - {24'd0, eb} + 127;
        end
        // One subtractor per quotient bit: its borrow is the bit, its difference the
        // next remainder when there is no borrow.
        q = 26'd0;
        for (i = 25; i >= 0; i = i - 1) begin
            diff = {1'b0, rem} - {3'b000, mb};
            q[i] = ~diff[26];
            if (!diff[26]) rem = diff[25:0];
            rem = {rem[24:0], 1'b0};
        end

        m = q[25:2];
        g = q[1];
        st = q[0] | (rem != 26'd0);
        up = g & (st | m[0]);
        mr = {1'b0, m} + {24'd0, up};
        if (mr[24]) begin
            mr = {2'b01, 23'd0};
            e = e + 1;
        end

        if (a_nan || b_nan || (a_inf && b_inf) || (a_zero && b_zero))
            r = 32'h7FC0_0000;
        else if (a_inf || b_zero)
            r = {s, 8'hFF, 23'd0};
        else if (a_zero || b_inf)
            r = {s, 31'd0};
        else if (e >= 255)
            r = {s, 8'hFF, 23'd0};
        else if (e <= 0)
            r = {s, 31'd0};  // below the smallest normal after rounding: flush
        else
            r = {s, e[7:0], mr[22:0]};
    end

    fp_delay #(.WIDTH(32), .LATENCY(LATENCY)) delay (.clk(clk), .d(r), .q(y));
endmodule
