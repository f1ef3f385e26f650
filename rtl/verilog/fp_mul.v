// fp_mul: IEEE-754 single-precision multiplication, y = a * b.
//
// The pipeline's multipliers (hwmodel operators `multiply` and `multiply_registered`,
// ALTFP_MULT in the thesis; the two differ only in LATENCY).
//
// Floating-point policy (shared by every arithmetic operator of this library and by
// its Rust reference `rtl::float_policy`, which is the normative text):
//   * a subnormal input is read as a zero of the same sign (the ALTFP cores flush
//     denormals too);
//   * the exact result is rounded to nearest, ties to even, to 24 significant bits
//     with an unbounded exponent range; if the rounded magnitude is below 2^-126 the
//     result is a zero with the exact result's sign, if it is 2^128 or more an
//     infinity: no result is ever subnormal;
//   * zero products carry the XOR of the signs;
//   * every NaN result (a NaN input, 0 * inf) is the quiet NaN 0x7FC00000.
//
// Datapath, in STAGES = 5 stages (fp_stage spreads LATENCY registers over them):
//   1. the 24 partial products of the significands and their compression to two rows
//      by a Wallace tree of carry-save adders (fp_mul_array); the special results and
//      the exponent sum beside it;
//   2. the two rows added on a prefix adder (fp_fast_add): the 48-bit product;
//   3. normalisation by at most one bit, the guard and sticky bits;
//   4. rounding to nearest even, the increment on a prefix adder;
//   5. the exponent range (overflow to infinity, flush below 2^-126) and the word.
//
// Verilog-2005, synthesizable; part of the rtprof `rtl` crate.
module fp_mul #(
    parameter LATENCY = 5
) (
    input clk,
    input [31:0] a,
    input [31:0] b,
    output [31:0] y
);
    localparam STAGES = 5;

    // Stage 1: specials, exponent, the product in carry-save form.
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
    reg special1;
    reg [31:0] word1;
    always @* begin
        special1 = 1'b1;
        if (a_nan || b_nan || (a_inf && b_zero) || (b_inf && a_zero))
            word1 = 32'h7FC0_0000;
        else if (a_inf || b_inf)
            word1 = {s, 8'hFF, 23'd0};
        else if (a_zero || b_zero)
            word1 = {s, 31'd0};
        else begin
            special1 = 1'b0;
            word1 = 32'd0;
        end
    end
    // Signed, 10 bits: ea + eb - 127 is in [-125, 381].
    wire [9:0] e1 = {2'b00, ea} + {2'b00, eb} - 10'd127;
    wire [47:0] row_s, row_c;
    fp_mul_array product (.a({1'b1, fa}), .b({1'b1, fb}), .s(row_s), .c(row_c));
    wire [139:0] s1_d = {special1, word1, s, e1, row_s, row_c};
    wire [139:0] s1;
    fp_stage #(.WIDTH(140), .LATENCY(LATENCY), .STAGES(STAGES), .STAGE(1)) st1 (.clk(clk), .d(s1_d), .q(s1));
    wire special2, s2;
    wire [31:0] word2;
    wire [9:0] e2;
    wire [47:0] row_s2, row_c2;
    assign {special2, word2, s2, e2, row_s2, row_c2} = s1;

    // Stage 2: the product.
    wire [47:0] p2;
    /* verilator lint_off UNUSEDSIGNAL */
    wire p_co2;
    /* verilator lint_on UNUSEDSIGNAL */
    fp_fast_add #(.W(48)) sum (.a(row_s2), .b(row_c2), .ci(1'b0), .s(p2), .co(p_co2));
    wire [91:0] s2_d = {special2, word2, s2, e2, p2};
    wire [91:0] s2q;
    fp_stage #(.WIDTH(92), .LATENCY(LATENCY), .STAGES(STAGES), .STAGE(2)) st2 (.clk(clk), .d(s2_d), .q(s2q));
    wire special3, s3;
    wire [31:0] word3;
    wire [9:0] e3;
    wire [47:0] p3;
    assign {special3, word3, s3, e3, p3} = s2q;

    // Stage 3: normalise (the product of two significands in [1, 2) is in [1, 4)).
    wire [23:0] m3 = p3[47] ? p3[47:24] : p3[46:23];
    wire g3 = p3[47] ? p3[23] : p3[22];
    // Written without a select between two reductions, which Yosys's opt_share would
    // turn into a coarse $mux that nothing maps.
    wire st3 = (|p3[21:0]) | (p3[47] & p3[22]);
    wire [9:0] e3n = e3 + {9'd0, p3[47]};
    wire up3 = g3 & (st3 | m3[0]);
    wire [68:0] s3_d = {special3, word3, s3, e3n, up3, m3};
    wire [68:0] s3q;
    fp_stage #(.WIDTH(69), .LATENCY(LATENCY), .STAGES(STAGES), .STAGE(3)) st3_ (.clk(clk), .d(s3_d), .q(s3q));
    wire special4, s4, up4;
    wire [31:0] word4;
    wire [9:0] e4;
    wire [23:0] m4;
    assign {special4, word4, s4, e4, up4, m4} = s3q;

    // Stage 4: round; a carry out of the significand is the next power of two.
    /* verilator lint_off UNUSEDSIGNAL */
    wire [23:0] mr4;
    /* verilator lint_on UNUSEDSIGNAL */
    wire carry4;
    fp_fast_add #(.W(24)) round (.a(m4), .b(24'd0), .ci(up4), .s(mr4), .co(carry4));
    wire [9:0] e4r = e4 + {9'd0, carry4};
    wire [22:0] frac4 = carry4 ? 23'd0 : mr4[22:0];
    wire [66:0] s4_d = {special4, word4, s4, e4r, frac4};
    wire [66:0] s4q;
    fp_stage #(.WIDTH(67), .LATENCY(LATENCY), .STAGES(STAGES), .STAGE(4)) st4 (.clk(clk), .d(s4_d), .q(s4q));
    wire special5, s5;
    wire [31:0] word5;
    wire [9:0] e5;
    wire [22:0] frac5;
    assign {special5, word5, s5, e5, frac5} = s4q;

    // Stage 5: the exponent range and the word.
    wire overflow = !e5[9] && (e5[8] || e5[7:0] == 8'hFF);
    wire underflow = e5[9] || (e5 == 10'd0);
    reg [31:0] r;
    always @* begin
        if (special5)
            r = word5;
        else if (overflow)
            r = {s5, 8'hFF, 23'd0};
        else if (underflow)
            r = {s5, 31'd0};  // below the smallest normal after rounding: flush
        else
            r = {s5, e5[7:0], frac5};
    end
    fp_stage #(.WIDTH(32), .LATENCY(LATENCY), .STAGES(STAGES), .STAGE(5)) st5 (.clk(clk), .d(r), .q(y));
endmodule

// fp_mul_array: the unsigned 24 x 24-bit significand product of fp_mul in carry-save
// form, a * b = s + c (mod 2^48, which holds the whole product): the 24 partial
// products reduced to two rows by a Wallace tree of carry-save adders (24, 16, 11, 8,
// 6, 4, 3, 2 rows: seven levels of one 3-input function per bit). A module of its own
// so that synthesis keeps it apart: the Yosys reports of `rtl::synth` count the logic
// of its instances as multiplier logic (Quartus maps a product to the embedded
// 9 x 9 / 18 x 18 multipliers; Yosys's synth_intel builds it from LUTs). With
// RTPROF_BEHAVIOURAL_ARITHMETIC defined (the whole-pipeline simulation, rtl::sim) the
// product is a plain `*` in s and c is zero: the same sum, and a Verilator model that
// builds in minutes; the operator tests simulate the tree itself.
/* verilator lint_off DECLFILENAME */
module fp_mul_array (
    input [23:0] a,
    input [23:0] b,
    output [47:0] s,
    output [47:0] c
);
`ifdef RTPROF_BEHAVIOURAL_ARITHMETIC
    assign s = {24'd0, a} * {24'd0, b};
    assign c = 48'd0;
`else
    localparam LEVELS = 7;
    // The rows left after `level` levels of 3:2 compression (a level turns each group
    // of three rows into two and passes the one or two left over).
    function integer rows_at;
        input integer level;
        case (level)
            0: rows_at = 24;
            1: rows_at = 16;
            2: rows_at = 11;
            3: rows_at = 8;
            4: rows_at = 6;
            5: rows_at = 4;
            6: rows_at = 3;
            default: rows_at = 2;
        endcase
    endfunction
    // The groups of three among rows_at(level) rows.
    function integer groups_at;
        input integer level;
        case (level)
            0: groups_at = 8;
            1: groups_at = 5;
            2: groups_at = 3;
            3: groups_at = 2;
            4: groups_at = 2;
            default: groups_at = 1;
        endcase
    endfunction
    genvar l, k;
    generate
        for (l = 0; l <= LEVELS; l = l + 1) begin : level
            wire [48*rows_at(l)-1:0] v;
            if (l == 0) begin : partial
                for (k = 0; k < 24; k = k + 1) begin : row
                    assign v[48*k +: 48] = b[k] ? ({24'd0, a} << k) : 48'd0;
                end
            end else begin : compress
                for (k = 0; k < groups_at(l - 1); k = k + 1) begin : csa
                    wire [47:0] x = level[l-1].v[48*(3*k) +: 48];
                    wire [47:0] y = level[l-1].v[48*(3*k+1) +: 48];
                    wire [47:0] z = level[l-1].v[48*(3*k+2) +: 48];
                    /* verilator lint_off UNUSEDSIGNAL */
                    wire [47:0] carry = (x & y) | (x & z) | (y & z);
                    /* verilator lint_on UNUSEDSIGNAL */
                    assign v[48*(2*k) +: 48] = x ^ y ^ z;
                    assign v[48*(2*k+1) +: 48] = {carry[46:0], 1'b0};
                end
                for (k = 0; k < rows_at(l - 1) - 3 * groups_at(l - 1); k = k + 1) begin : pass
                    assign v[48*(2*groups_at(l - 1) + k) +: 48] =
                        level[l-1].v[48*(3*groups_at(l - 1) + k) +: 48];
                end
            end
        end
    endgenerate
    assign s = level[LEVELS].v[47:0];
    assign c = level[LEVELS].v[95:48];
`endif
endmodule
/* verilator lint_on DECLFILENAME */
