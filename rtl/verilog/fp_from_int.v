// fp_from_int: signed 32-bit integer to IEEE-754 single precision, y = (float) a.
//
// The pipeline's integer-to-float conversions (the screen iterator turns its pixel
// column and row counters into floats; hwmodel operator `convert`, ALTFP_CONVERT).
//
// a is two's complement; the result is rounded to nearest, ties to even (integers of
// more than 24 significant bits are not exact: 2^24 + 1 -> 2^24, 2^24 + 3 -> 2^24 + 4).
// 0 gives +0; i32::MIN gives -2^31 exactly. Results are always normal or zero, so the
// library's denormal policy has nothing to do here.
//
// Datapath, in STAGES = 6 stages of at most a few LUT levels each (fp_stage spreads
// LATENCY registers over them):
//   1. the magnitude: -a is ~a + 1 on a prefix adder (fp_fast_add);
//   2. the leading-zero count (fp_lzc);
//   3. the left shift that puts the leading one at bit 31, and the exponent 158 - lz;
//   4. rounding at bit 8 (guard, sticky), the increment on a prefix adder;
//   5. the exponent's carry when rounding overflows to the next power of two;
//   6. the result word (zero for a = 0).
//
// Verilog-2005, synthesizable; part of the rtprof `rtl` crate.
module fp_from_int #(
    parameter LATENCY = 6
) (
    input clk,
    input [31:0] a,
    output [31:0] y
);
    localparam STAGES = 6;

    // Stage 1: sign, zero flag, magnitude.
    wire [31:0] neg;
    /* verilator lint_off UNUSEDSIGNAL */
    wire neg_co;
    /* verilator lint_on UNUSEDSIGNAL */
    fp_fast_add #(.W(32), .NEG_B(1)) negate (.a(32'd0), .b(a), .ci(1'b1), .s(neg), .co(neg_co));
    wire [33:0] s1_d = {a[31], a == 32'd0, a[31] ? neg : a};
    wire [33:0] s1;
    fp_stage #(.WIDTH(34), .LATENCY(LATENCY), .STAGES(STAGES), .STAGE(1)) st1 (.clk(clk), .d(s1_d), .q(s1));

    // Stage 2: leading zeros of the magnitude.
    wire [31:0] mag2 = s1[31:0];
    wire [5:0] lz;
    fp_lzc #(.N(5)) count (.x(mag2), .lz(lz));
    wire [39:0] s2_d = {s1[33:32], lz, mag2};
    wire [39:0] s2;
    fp_stage #(.WIDTH(40), .LATENCY(LATENCY), .STAGES(STAGES), .STAGE(2)) st2 (.clk(clk), .d(s2_d), .q(s2));

    // Stage 3: normalise; leading one at bit 31 is 2^(31 - lz), biased 158 - lz.
    wire [31:0] norm3 = s2[31:0] << s2[37:32];
    wire [7:0] e3 = 8'd158 - {2'b00, s2[37:32]};
    wire [41:0] s3_d = {s2[39:38], e3, norm3};
    wire [41:0] s3;
    fp_stage #(.WIDTH(42), .LATENCY(LATENCY), .STAGES(STAGES), .STAGE(3)) st3 (.clk(clk), .d(s3_d), .q(s3));

    // Stage 4: round to nearest even at bit 8.
    wire [31:0] norm4 = s3[31:0];
    wire up4 = norm4[7] & ((|norm4[6:0]) | norm4[8]);
    wire [23:0] mr4;
    wire carry4;
    fp_fast_add #(.W(24)) round (.a(norm4[31:8]), .b(24'd0), .ci(up4), .s(mr4), .co(carry4));
    wire [34:0] s4_d = {s3[41:40], s3[39:32], carry4, mr4};
    wire [34:0] s4;
    fp_stage #(.WIDTH(35), .LATENCY(LATENCY), .STAGES(STAGES), .STAGE(4)) st4 (.clk(clk), .d(s4_d), .q(s4));

    // Stage 5: a carry out of the significand is the next power of two (fraction 0).
    wire [7:0] e5 = s4[32:25] + {7'd0, s4[24]};
    /* verilator lint_off UNUSEDSIGNAL */
    wire [23:0] mr5 = s4[24] ? 24'd0 : s4[23:0];
    /* verilator lint_on UNUSEDSIGNAL */
    wire [32:0] s5_d = {s4[34:33], e5, mr5[22:0]};
    wire [32:0] s5;
    fp_stage #(.WIDTH(33), .LATENCY(LATENCY), .STAGES(STAGES), .STAGE(5)) st5 (.clk(clk), .d(s5_d), .q(s5));

    // Stage 6: the word.
    wire [31:0] r = s5[31] ? 32'd0 : {s5[32], s5[30:0]};
    fp_stage #(.WIDTH(32), .LATENCY(LATENCY), .STAGES(STAGES), .STAGE(6)) st6 (.clk(clk), .d(r), .q(y));
endmodule
