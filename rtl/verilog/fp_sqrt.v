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
// by a restoring digit recurrence, one result bit per iteration: 24 significand bits,
// a guard bit, and a sticky bit from the remainder. Iteration n (n = 0 .. 24) compares
// the partial remainder, n + 3 bits wide, with the trial root on a prefix adder
// (fp_fast_add) and keeps the difference when it is not negative. STAGES = 13 stages
// (fp_stage spreads LATENCY registers over them, extra registers where LATENCY is
// larger): stage 1 unpacks, decides the special results and runs the three narrowest
// iterations; stages 2 .. 12 run two iterations each; stage 13 rounds and packs.
//
// Verilog-2005, synthesizable; part of the rtprof `rtl` crate.
module fp_sqrt #(
    parameter LATENCY = 16
) (
    input clk,
    input [31:0] a,
    output [31:0] y
);
    localparam STAGES = 13;
    localparam ITERATIONS = 25;

    wire sa = a[31];
    wire [7:0] ea = a[30:23];
    wire [22:0] fa = a[22:0];
    wire a_zero = (ea == 8'd0);
    wire a_inf = (ea == 8'hFF) && (fa == 23'd0);
    wire a_nan = (ea == 8'hFF) && (fa != 23'd0);
    wire special = a_nan || (sa && !a_zero) || a_zero || a_inf;
    wire [31:0] word = (a_nan || (sa && !a_zero)) ? 32'h7FC0_0000
        : a_zero ? {sa, 31'd0} : 32'h7F80_0000;
    // Unbiased exponent E = ea - 127: E even (ea odd) scales by 2^25, E odd by 2^26, so
    // that the radicand is in [2^48, 2^50) and its root in [2^24, 2^25). The result's
    // biased exponent is floor(E / 2) + 127 = (ea + 127) >> 1.
    wire [49:0] x = ea[0] ? {1'b0, 1'b1, fa, 25'd0} : {1'b1, fa, 26'd0};
    /* verilator lint_off UNUSEDSIGNAL */
    wire [8:0] e_sum = {1'b0, ea} + 9'd127;
    /* verilator lint_on UNUSEDSIGNAL */
    // The state between iterations: special, word, exponent, radicand, root, remainder.
    localparam SW = 1 + 32 + 8 + 50 + 25 + 28;
    wire [SW-1:0] start = {special, word, e_sum[8:1], x, 25'd0, 28'd0};

    genvar n;
    generate
        for (n = 0; n < ITERATIONS; n = n + 1) begin : it
            localparam W = n + 3;
            localparam I = ITERATIONS - 1 - n;
            wire [SW-1:0] in;
            if (n == 0) begin : first
                assign in = start;
            end else begin : next
                assign in = it[n-1].out;
            end
            wire [40:0] side = in[SW-1 -: 41];
            wire [49:0] xs = in[102:53];
            wire [24:0] root = in[52:28];
            // The remainder below 2 root + 1 < 2^(n+1) before this iteration, so the
            // shifted one fits in n + 3 bits and the trial root {root, 01} in n + 2.
            /* verilator lint_off UNUSEDSIGNAL */
            wire [27:0] rem = in[27:0];
            wire [27:0] trial = {1'b0, root, 2'b01};
            /* verilator lint_on UNUSEDSIGNAL */
            wire [27:0] shifted = {rem[25:0], xs[2*I+1], xs[2*I]};
            wire [W-1:0] diff;
            wire fits;
            fp_fast_add #(.W(W), .NEG_B(1)) sub (.a(shifted[W-1:0]), .b(trial[W-1:0]), .ci(1'b1),
                .s(diff), .co(fits));
            wire [27:0] rem_next = fits ? {{(28-W){1'b0}}, diff} : shifted;
            wire [SW-1:0] done = {side, xs, root[23:0], fits, rem_next};
            wire [SW-1:0] out;
            // A stage ends after iterations 2, 4, ..., 24: stage n / 2 (shifts: the
            // library's sources have no division operator).
            if (n >= 2 && (n & 1) == 0) begin : boundary
                fp_stage #(.WIDTH(SW), .LATENCY(LATENCY), .STAGES(STAGES), .STAGE(n >> 1))
                    regs (.clk(clk), .d(done), .q(out));
            end else begin : wire_
                assign out = done;
            end
            /* verilator lint_off UNUSEDSIGNAL */
            wire unused = root[24];
            /* verilator lint_on UNUSEDSIGNAL */
        end
    endgenerate

    // Stage 13: round to nearest even (a square root is never a tie); a carry out of
    // the significand is the next power of two.
    wire [SW-1:0] last = it[ITERATIONS-1].out;
    wire special13 = last[SW-1];
    wire [31:0] word13 = last[SW-2 -: 32];
    wire [7:0] e13 = last[SW-34 -: 8];
    wire [24:0] root13 = last[52:28];
    wire [27:0] rem13 = last[27:0];
    wire up = root13[0] & ((rem13 != 28'd0) | root13[1]);
    /* verilator lint_off UNUSEDSIGNAL */
    wire [23:0] mr;
    /* verilator lint_on UNUSEDSIGNAL */
    wire carry;
    fp_fast_add #(.W(24)) round (.a(root13[24:1]), .b(24'd0), .ci(up), .s(mr), .co(carry));
    wire [7:0] e_r = e13 + {7'd0, carry};
    wire [31:0] r = special13 ? word13 : {1'b0, e_r, carry ? 23'd0 : mr[22:0]};
    fp_stage #(.WIDTH(32), .LATENCY(LATENCY), .STAGES(STAGES), .STAGE(13)) st13 (.clk(clk), .d(r), .q(y));
    /* verilator lint_off UNUSEDSIGNAL */
    wire [49:0] unused_x = last[102:53];
    /* verilator lint_on UNUSEDSIGNAL */
endmodule
