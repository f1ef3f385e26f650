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
// Datapath: a restoring radix-2 digit recurrence (no `/` operator): 26 quotient bits
// (24 significand bits and a guard bit after pre-normalising the dividend so that the
// first bit is one) and a sticky bit from the final remainder. A quotient of two
// 24-bit significands is never exactly halfway between two floats, so ties cannot
// occur, but the rounding is the general one. Each iteration compares the partial
// remainder with the divisor on a prefix adder (fp_fast_add, about 5 LUT levels) and
// keeps the difference when it is not negative, so two iterations fill a stage.
// STAGES = 15 (fp_stage spreads LATENCY registers over them):
//   1. unpack, special results, the exponent; the first quotient bit, which the
//      pre-normalisation makes a one: both candidate remainders (ma - mb, 2 ma - mb)
//      are formed beside the comparison ma < mb that picks one;
//   2 .. 13. quotient bits 2 .. 25, two per stage;
//   14. the last quotient bit, the sticky bit and the rounding decision;
//   15. the increment (a prefix adder), the exponent range and the word.
// Two iterations of about 5 levels fill a stage of the 12-level goal, so the 26
// iterations alone need 13 stages: the thesis's latency of 6 (ALTFP_DIV, a table and
// multipliers) cannot hold them; the operator library's divide row says so.
//
// Verilog-2005, synthesizable; part of the rtprof `rtl` crate.
module fp_div #(
    parameter LATENCY = 15
) (
    input clk,
    input [31:0] a,
    input [31:0] b,
    output [31:0] y
);
    localparam STAGES = 15;
    localparam ITERATIONS = 26;

    // Stage 1: specials, exponent, the first quotient bit.
    wire s = a[31] ^ b[31];
    wire [7:0] ea = a[30:23];
    wire [7:0] eb = b[30:23];
    wire [22:0] fa = a[22:0];
    wire [22:0] fb = b[22:0];
    wire a_zero = (ea == 8'd0);
    wire b_zero = (eb == 8'd0);
    wire a_inf = (ea == 8'hFF) && (fa == 23'd0);
    wire b_inf = (eb == 8'hFF) && (fb == 23'd0);
    wire a_nan = (ea == 8'hFF) && (fa != 23'd0);
    wire b_nan = (eb == 8'hFF) && (fb != 23'd0);
    reg special;
    reg [31:0] word;
    always @* begin
        special = 1'b1;
        if (a_nan || b_nan || (a_inf && b_inf) || (a_zero && b_zero))
            word = 32'h7FC0_0000;
        else if (a_inf || b_zero)
            word = {s, 8'hFF, 23'd0};
        else if (a_zero || b_inf)
            word = {s, 31'd0};
        else begin
            special = 1'b0;
            word = 32'd0;
        end
    end
    wire [23:0] ma = {1'b1, fa};
    wire [23:0] mb = {1'b1, fb};
    // ma >= mb: the remainder starts at ma, else at 2 ma; either way in [mb, 2 mb), so
    // the first quotient bit is one and the remainder after it is the difference.
    /* verilator lint_off UNUSEDSIGNAL */
    wire [23:0] d1;
    wire [24:0] d2;
    wire co2;
    /* verilator lint_on UNUSEDSIGNAL */
    wire a_ge_b;
    fp_fast_add #(.W(24), .NEG_B(1)) first1 (.a(ma), .b(mb), .ci(1'b1), .s(d1), .co(a_ge_b));
    fp_fast_add #(.W(25), .NEG_B(1)) first2 (.a({ma, 1'b0}), .b({1'b0, mb}), .ci(1'b1), .s(d2), .co(co2));
    // Signed, 10 bits: ea - eb + 127 is in [-126, 380].
    wire [9:0] e = {2'b00, ea} - {2'b00, eb} + (a_ge_b ? 10'd127 : 10'd126);
    // The remainder after the first bit is below mb < 2^24; shifted, below 2^25.
    wire [25:0] rem1 = a_ge_b ? {1'b0, d1, 1'b0} : {d2[24:0], 1'b0};
    // The state between iterations: special, word, sign, exponent, divisor, quotient,
    // remainder.
    localparam SW = 1 + 32 + 1 + 10 + 24 + 26 + 26;
    wire [SW-1:0] start = {special, word, s, e, mb, 26'd1, rem1};
    wire [SW-1:0] after_first;
    fp_stage #(.WIDTH(SW), .LATENCY(LATENCY), .STAGES(STAGES), .STAGE(1))
        st1 (.clk(clk), .d(start), .q(after_first));

    // Quotient bits 2 .. 26 (iterations 1 .. 25).
    genvar n;
    generate
        for (n = 1; n < ITERATIONS; n = n + 1) begin : it
            wire [SW-1:0] in;
            if (n == 1) begin : first
                assign in = after_first;
            end else begin : next
                assign in = it[n-1].out;
            end
            wire [43:0] side = in[SW-1 -: 44];
            wire [23:0] divisor = in[75:52];
            /* verilator lint_off UNUSEDSIGNAL */
            wire [25:0] q = in[51:26];
            /* verilator lint_on UNUSEDSIGNAL */
            wire [25:0] rem = in[25:0];
            // The remainder is below 2 mb < 2^25: rem >= mb is the carry of rem - mb.
            wire [25:0] diff;
            wire fits;
            fp_fast_add #(.W(26), .NEG_B(1)) sub (.a(rem), .b({2'b00, divisor}), .ci(1'b1), .s(diff),
                .co(fits));
            /* verilator lint_off UNUSEDSIGNAL */
            wire [25:0] kept = fits ? diff : rem;
            /* verilator lint_on UNUSEDSIGNAL */
            wire [SW-1:0] done = {side, divisor, q[24:0], fits, kept[24:0], 1'b0};
            wire [SW-1:0] out;
            // Stages 2 .. 13 end after iterations 2, 4, ..., 24 (stage n / 2 + 1); the
            // last iteration shares stage 14 with the rounding decision.
            if (n >= 2 && (n & 1) == 0) begin : boundary
                fp_stage #(.WIDTH(SW), .LATENCY(LATENCY), .STAGES(STAGES), .STAGE((n >> 1) + 1))
                    regs (.clk(clk), .d(done), .q(out));
            end else begin : wire_
                assign out = done;
            end
        end
    endgenerate

    // Stage 14: sticky bit and rounding decision.
    wire [SW-1:0] last = it[ITERATIONS-1].out;
    wire special14 = last[SW-1];
    wire [31:0] word14 = last[SW-2 -: 32];
    wire s14 = last[SW-34];
    wire [9:0] e14 = last[SW-35 -: 10];
    wire [25:0] q14 = last[51:26];
    wire [25:0] rem14 = last[25:0];
    wire st14 = q14[0] | (rem14 != 26'd0);
    wire up14 = q14[1] & (st14 | q14[2]);
    /* verilator lint_off UNUSEDSIGNAL */
    wire [75:0] unused14 = last[75:0];
    /* verilator lint_on UNUSEDSIGNAL */
    wire [68:0] s14_d = {special14, word14, s14, e14, up14, q14[25:2]};
    wire [68:0] s14q;
    fp_stage #(.WIDTH(69), .LATENCY(LATENCY), .STAGES(STAGES), .STAGE(14))
        st14_ (.clk(clk), .d(s14_d), .q(s14q));
    wire special15, s15, up15;
    wire [31:0] word15;
    wire [9:0] e15;
    wire [23:0] m15;
    assign {special15, word15, s15, e15, up15, m15} = s14q;

    // Stage 15: round; a carry out of the significand is the next power of two.
    /* verilator lint_off UNUSEDSIGNAL */
    wire [23:0] mr;
    /* verilator lint_on UNUSEDSIGNAL */
    wire carry;
    fp_fast_add #(.W(24)) round (.a(m15), .b(24'd0), .ci(up15), .s(mr), .co(carry));
    wire [9:0] e_r = e15 + {9'd0, carry};
    wire overflow = !e_r[9] && (e_r[8] || e_r[7:0] == 8'hFF);
    wire underflow = e_r[9] || (e_r == 10'd0);
    reg [31:0] r;
    always @* begin
        if (special15)
            r = word15;
        else if (overflow)
            r = {s15, 8'hFF, 23'd0};
        else if (underflow)
            r = {s15, 31'd0};  // below the smallest normal after rounding: flush
        else
            r = {s15, e_r[7:0], carry ? 23'd0 : mr[22:0]};
    end
    fp_stage #(.WIDTH(32), .LATENCY(LATENCY), .STAGES(STAGES), .STAGE(15)) st15 (.clk(clk), .d(r), .q(y));
endmodule
