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
// Datapath, in STAGES = 7 stages of a few LUT levels each (fp_stage spreads LATENCY
// registers over them; prefix adders, fp_fast_add, and a leading-zero tree, fp_lzc,
// keep each stage shallow):
//   1. unpack; the special results (NaN, infinities, zeros) are decided here and
//      travel beside the datapath; the operand of larger magnitude is found (a 31-bit
//      compare) and the exponent difference taken;
//   2. the smaller significand is aligned with three extra bits (guard, round, and a
//      sticky bit jammed into the lowest bit);
//   3. the significands are added or subtracted;
//   4. the leading zeros of the sum, and whether it is zero;
//   5. normalisation: a sum carry shifts right by one, a difference left by the count;
//   6. rounding to nearest even at bit 3;
//   7. the exponent range (overflow to infinity, flush below 2^-126) and the word.
// Jamming keeps the rounding exact: the sticky bit is non-zero only for exponent
// differences of 4 or more, where a difference loses at most one leading bit.
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
    localparam STAGES = 7;

    // Stage 1: classify, decide the special results, order the operands.
    wire sa = a[31];
    wire sb = b[31] ^ sub;
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
    reg special1;
    reg [31:0] word1;
    always @* begin
        special1 = 1'b1;
        if (a_nan || b_nan || (a_inf && b_inf && (sa != sb)))
            word1 = 32'h7FC0_0000;
        else if (a_inf)
            word1 = {sa, 8'hFF, 23'd0};
        else if (b_inf)
            word1 = {sb, 8'hFF, 23'd0};
        else if (a_zero && b_zero)
            word1 = {sa & sb, 31'd0};
        else if (b_zero)
            word1 = {sa, ea, fa};
        else if (a_zero)
            word1 = {sb, eb, fb};
        else begin
            special1 = 1'b0;
            word1 = 32'd0;
        end
    end
    // |a| >= |b| is the carry out of |a| - |b|.
    wire a_ge_b;
    /* verilator lint_off UNUSEDSIGNAL */
    wire [30:0] mag_diff;
    wire [7:0] dab_full = ea - eb;
    wire [7:0] dba_full = eb - ea;
    /* verilator lint_on UNUSEDSIGNAL */
    fp_fast_add #(.W(31), .NEG_B(1)) order (.a({ea, fa}), .b({eb, fb}), .ci(1'b1), .s(mag_diff), .co(a_ge_b));
    wire swap = ~a_ge_b;
    wire [96:0] s1_d = {special1, word1, swap ? sb : sa, swap ? eb : ea, swap ? fb : fa,
        swap ? fa : fb, swap ? dba_full : dab_full, sa ^ sb};
    wire [96:0] s1;
    fp_stage #(.WIDTH(97), .LATENCY(LATENCY), .STAGES(STAGES), .STAGE(1)) st1 (.clk(clk), .d(s1_d), .q(s1));
    wire special2, s_big2, eff_sub2;
    wire [31:0] word2;
    wire [7:0] e_big2, d2;
    wire [22:0] f_big2, f_small2;
    assign {special2, word2, s_big2, e_big2, f_big2, f_small2, d2, eff_sub2} = s1;

    // Stage 2: align the smaller significand; bits shifted out are jammed into bit 0.
    wire [26:0] x_small = {1'b1, f_small2, 3'b000};
    wire far = (d2 >= 8'd27);
    wire [26:0] shifted = x_small >> d2[4:0];
    wire [26:0] mask = (27'd1 << d2[4:0]) - 27'd1;
    wire sticky = far | (|(x_small & mask));
    wire [26:0] x_sh = far ? 27'd1 : {shifted[26:1], shifted[0] | sticky};
    wire [92:0] s2_d = {special2, word2, s_big2, e_big2, f_big2, x_sh, eff_sub2};
    wire [92:0] s2;
    fp_stage #(.WIDTH(93), .LATENCY(LATENCY), .STAGES(STAGES), .STAGE(2)) st2 (.clk(clk), .d(s2_d), .q(s2));
    wire special3, s_big3, eff_sub3;
    wire [31:0] word3;
    wire [7:0] e_big3;
    wire [22:0] f_big3;
    wire [26:0] x_sh3;
    assign {special3, word3, s_big3, e_big3, f_big3, x_sh3, eff_sub3} = s2;

    // Stage 3: add or subtract (the larger minus the smaller: never negative).
    wire [27:0] addend = eff_sub3 ? ~{1'b0, x_sh3} : {1'b0, x_sh3};
    wire [27:0] sum3;
    /* verilator lint_off UNUSEDSIGNAL */
    wire sum_co3;
    /* verilator lint_on UNUSEDSIGNAL */
    fp_fast_add #(.W(28)) add (.a({2'b01, f_big3, 3'b000}), .b(addend), .ci(eff_sub3), .s(sum3), .co(sum_co3));
    wire [69:0] s3_d = {special3, word3, s_big3, e_big3, sum3};
    wire [69:0] s3;
    fp_stage #(.WIDTH(70), .LATENCY(LATENCY), .STAGES(STAGES), .STAGE(3)) st3 (.clk(clk), .d(s3_d), .q(s3));
    wire special4, s_big4;
    wire [31:0] word4;
    wire [7:0] e_big4;
    wire [27:0] sum4;
    assign {special4, word4, s_big4, e_big4, sum4} = s3;

    // Stage 4: leading zeros below a carry (ones pad the count's input, so a zero sum
    // counts 27 and never more); an exact cancellation is a zero sum.
    /* verilator lint_off UNUSEDSIGNAL */
    wire [5:0] lz_full;
    /* verilator lint_on UNUSEDSIGNAL */
    fp_lzc #(.N(5)) count (.x({sum4[26:0], 5'b11111}), .lz(lz_full));
    wire zero4 = (sum4 == 28'd0);
    wire [75:0] s4_d = {special4, word4, s_big4, e_big4, sum4, zero4, lz_full[4:0]};
    wire [75:0] s4;
    fp_stage #(.WIDTH(76), .LATENCY(LATENCY), .STAGES(STAGES), .STAGE(4)) st4 (.clk(clk), .d(s4_d), .q(s4));
    wire special5, s_big5, zero5;
    wire [31:0] word5;
    wire [7:0] e_big5;
    wire [27:0] sum5;
    wire [4:0] lz5;
    assign {special5, word5, s_big5, e_big5, sum5, zero5, lz5} = s4;

    // Stage 5: normalise; the exponent is signed, 10 bits (it can fall below 1).
    wire [26:0] m5 = sum5[27] ? {sum5[27:2], sum5[1] | sum5[0]} : (sum5[26:0] << lz5);
    wire [9:0] e5 = sum5[27] ? ({2'b00, e_big5} + 10'd1) : ({2'b00, e_big5} - {5'd0, lz5});
    wire [71:0] s5_d = {special5, word5, s_big5, zero5, e5, m5};
    wire [71:0] s5;
    fp_stage #(.WIDTH(72), .LATENCY(LATENCY), .STAGES(STAGES), .STAGE(5)) st5 (.clk(clk), .d(s5_d), .q(s5));
    wire special6, s_big6, zero6;
    wire [31:0] word6;
    wire [9:0] e6;
    wire [26:0] m6;
    assign {special6, word6, s_big6, zero6, e6, m6} = s5;

    // Stage 6: round to nearest even at bit 3 (m6[26] is the hidden one); a carry out
    // of the significand is the next power of two.
    wire up6 = m6[2] & ((m6[1] | m6[0]) | m6[3]);
    /* verilator lint_off UNUSEDSIGNAL */
    wire [23:0] mr6;
    /* verilator lint_on UNUSEDSIGNAL */
    wire carry6;
    fp_fast_add #(.W(24)) round (.a(m6[26:3]), .b(24'd0), .ci(up6), .s(mr6), .co(carry6));
    wire [9:0] e6r = e6 + {9'd0, carry6};
    wire [22:0] frac6 = carry6 ? 23'd0 : mr6[22:0];
    wire [67:0] s6_d = {special6, word6, s_big6, zero6, e6r, frac6};
    wire [67:0] s6;
    fp_stage #(.WIDTH(68), .LATENCY(LATENCY), .STAGES(STAGES), .STAGE(6)) st6 (.clk(clk), .d(s6_d), .q(s6));
    wire special7, s_big7, zero7;
    wire [31:0] word7;
    wire [9:0] e7;
    wire [22:0] frac7;
    assign {special7, word7, s_big7, zero7, e7, frac7} = s6;

    // Stage 7: the exponent range and the word.
    wire overflow = !e7[9] && (e7[8] || e7[7:0] == 8'hFF);
    wire underflow = e7[9] || (e7 == 10'd0);
    reg [31:0] r;
    always @* begin
        if (special7)
            r = word7;
        else if (zero7)
            r = 32'd0;  // exact cancellation: +0 when rounding to nearest
        else if (overflow)
            r = {s_big7, 8'hFF, 23'd0};
        else if (underflow)
            r = {s_big7, 31'd0};  // below the smallest normal after rounding: flush
        else
            r = {s_big7, e7[7:0], frac7};
    end
    fp_stage #(.WIDTH(32), .LATENCY(LATENCY), .STAGES(STAGES), .STAGE(7)) st7 (.clk(clk), .d(r), .q(y));
endmodule
