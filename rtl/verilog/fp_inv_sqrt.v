// fp_inv_sqrt: IEEE-754 single-precision reciprocal square root, y = 1 / sqrt(a).
//
// The pipeline's reciprocal root (hwmodel operator `inv_sqrt`, the thesis's
// ALTFP_INV_SQRT): the scale factor of vector normalisation.
//
// Semantics: exactly fp_div(1.0, fp_sqrt(a)), i.e. `rtl::float_policy::inv_sqrt`, the
// normalisation the software and the emulator compute (a root, then a reciprocal).
// Each step follows the library's floating-point policy and rounds to nearest, ties to
// even, so the result is rounded twice (intended: it is what the reference computes;
// a correctly rounded 1/sqrt differs in the last bit for some inputs):
//   * a subnormal input is read as a zero of the same sign: 1 / sqrt(+0) = +inf, and
//     1 / sqrt(-0) = 1 / -0 = -inf (likewise for negative subnormals);
//   * 1 / sqrt(+inf) = +0; the root of a positive normal number is normal, and so is
//     its reciprocal, so neither flushing nor overflow occurs for finite inputs;
//   * every NaN result (a NaN input, a negative non-zero input, -inf) is the quiet NaN
//     0x7FC00000.
//
// Datapath: fp_sqrt followed by fp_div with the constant dividend 1.0 (so this module
// needs fp_sqrt.v and fp_div.v besides the shared building blocks), each pipelined in
// its own stages: LATENCY is split between them in proportion to their stage counts
// (13 and 15), so at the library's latency, 28, each runs at its own design point
// with at most its own depth between registers. 28 rather than the thesis's 26
// (ALTFP_INV_SQRT, built on multipliers): the two digit recurrences (51 iterations of
// about 5 LUT levels) and their two roundings do not fit 26 stages of 12 levels.
//
// Verilog-2005, synthesizable; part of the rtprof `rtl` crate.
module fp_inv_sqrt #(
    parameter LATENCY = 28
) (
    input clk,
    input [31:0] a,
    output [31:0] y
);
    localparam SQRT_STAGES = 13;
    localparam DIV_STAGES = 15;
    // floor(LATENCY * 13 / 28), counted (the library's sources have no division).
    function integer sqrt_share;
        input integer latency;
        integer k;
        begin
            k = 0;
            while ((k + 1) * (SQRT_STAGES + DIV_STAGES) <= latency * SQRT_STAGES)
                k = k + 1;
            sqrt_share = k;
        end
    endfunction
    localparam SQRT_LATENCY = sqrt_share(LATENCY);
    wire [31:0] root;

    fp_sqrt #(.LATENCY(SQRT_LATENCY)) sqrt_core (.clk(clk), .a(a), .y(root));
    fp_div #(.LATENCY(LATENCY - SQRT_LATENCY)) div_core (.clk(clk), .a(32'h3F80_0000), .b(root), .y(y));
endmodule
