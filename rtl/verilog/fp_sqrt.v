// fp_sqrt: IEEE-754 single-precision square root, y = sqrt(a).
//
// The pipeline's square root (hwmodel operator `sqrt`, ALTFP_SQRT in the thesis): the
// discriminant's root in the ray-primitive solver and the length in normalisation.
//
// Floating-point policy (shared by every arithmetic operator of this library and by
// its Rust reference `rtl::float_policy`, which is the normative text):
//   * a subnormal input is read as a zero of the same sign, so sqrt of a negative
//     subnormal is -0 (sqrt(-0) = -0 as in IEEE 754);
//   * round to nearest, ties to even (a square root is never a tie); the root of a
//     positive normal number is always normal, so neither flushing nor overflow
//     applies;
//   * sqrt(+inf) = +inf; every NaN result (a NaN input, a negative non-zero input,
//     -inf) is the quiet NaN 0x7FC00000.
//
// Datapath: the significand is scaled to an even power of two (shifted by 25 or 26
// bits, depending on the exponent's parity) and its 25-bit integer square root taken
// by a restoring digit recurrence, one result bit per `for` iteration, in the
// combinational core (no `/` or `%`): 24 significand bits, a guard bit, and a sticky
// bit from the remainder. A combinational core followed by a LATENCY-deep register
// pipeline (fp_delay).
//
// Verilog-2005, synthesizable; part of the rtprof `rtl` crate.
module fp_sqrt #(
    parameter LATENCY = 16
) (
    input clk,
    input [31:0] a,
    output [31:0] y
);
    reg [31:0] r;

    reg sa, a_zero, a_inf, a_nan, g, st, up;
    reg [7:0] ea;
    reg [22:0] fa;
    reg [49:0] x;
    reg [27:0] rem;
    reg [26:0] trial;
    // mr[23] is the hidden one: it is not stored.
    /* verilator lint_off UNUSEDSIGNAL */
    reg [24:0] root, mr;
    /* verilator lint_on UNUSEDSIGNAL */
    reg [8:0] e;
    integer i;

    always @* begin
        sa = a[31];
        ea = a[30:23];
        fa = a[22:0];
        a_zero = (ea == 8'd0);
        a_inf = (ea == 8'hFF) && (fa == 23'd0);
        a_nan = (ea == 8'hFF) && (fa != 23'd0);

        // Unbiased exponent E = ea - 127: E even (ea odd) scales by 2^25, E odd by
        // 2^26, so that the radicand is in [2^48, 2^50) and its root in [2^24, 2^25).
        if (ea[0])
            x = {1'b0, 1'b1, fa, 25'd0};
        else
            x = {1'b1, fa, 26'd0};
        // The result's biased exponent: floor(E / 2) + 127 = (ea + 127) >> 1.
        e = ({1'b0, ea} + 9'd127) >> 1;

        rem = 28'd0;
        root = 25'd0;
        for (i = 24; i >= 0; i = i - 1) begin
            rem = {rem[25:0], x[2*i+1], x[2*i]};
            trial = {root, 2'b01};
            if (rem >= {1'b0, trial}) begin
                rem = rem - {1'b0, trial};
                root = {root[23:0], 1'b1};
            end else begin
                root = {root[23:0], 1'b0};
            end
        end

        g = root[0];
        st = (rem != 28'd0);
        up = g & (st | root[1]);
        mr = {1'b0, root[24:1]} + {24'd0, up};
        if (mr[24]) begin
            mr = {2'b01, 23'd0};
            e = e + 9'd1;
        end

        if (a_nan || (sa && !a_zero))
            r = 32'h7FC0_0000;
        else if (a_zero)
            r = {sa, 31'd0};
        else if (a_inf)
            r = 32'h7F80_0000;
        else
            r = {1'b0, e[7:0], mr[22:0]};
    end

    fp_delay #(.WIDTH(32), .LATENCY(LATENCY)) delay (.clk(clk), .d(r), .q(y));
endmodule
