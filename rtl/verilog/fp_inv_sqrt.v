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
// Datapath: the combinational cores of fp_sqrt and fp_div (both instantiated with
// LATENCY = 0, so this module needs fp_sqrt.v, fp_div.v and fp_delay.v), the divider's
// dividend the constant 1.0, followed by one LATENCY-deep register pipeline
// (fp_delay); the two recurrences are deep logic, meant to be spread over the
// registers by retiming.
//
// Verilog-2005, synthesizable; part of the rtprof `rtl` crate.
module fp_inv_sqrt #(
    parameter LATENCY = 26
) (
    input clk,
    input [31:0] a,
    output [31:0] y
);
    wire [31:0] root, r;

    fp_sqrt #(.LATENCY(0)) sqrt_core (.clk(clk), .a(a), .y(root));
    fp_div #(.LATENCY(0)) div_core (.clk(clk), .a(32'h3F80_0000), .b(root), .y(r));

    fp_delay #(.WIDTH(32), .LATENCY(LATENCY)) delay (.clk(clk), .d(r), .q(y));
endmodule
