// fp_fast_sqrt: the thesis's square-root bit trick (8.3.1), y = (a + 0x3F800000) >> 1.
//
// An integer operation on the bit pattern: a 32-bit add whose carry out is dropped,
// then a logical shift right by one (a wire). This is exactly rtprof's software
// `bit_trick_sqrt(x, 0x3F80_0000)` (`wrapping_add`, then `>>`) and
// `rtl::float_policy::fast_sqrt`. No floating-point policy applies: no flushing of
// subnormals, no NaN canonicalisation; negative inputs, zero, infinities and NaNs give
// whatever the integer formula gives (the ray caster only takes roots of positive
// normal numbers). For positive normal inputs the result overestimates sqrt by up to
// 6.07 %.
//
// Verilog-2005, synthesizable; part of the rtprof `rtl` crate.
module fp_fast_sqrt #(
    parameter LATENCY = 1
) (
    input clk,
    input [31:0] a,
    output [31:0] y
);
    // The shift drops sum[0].
    /* verilator lint_off UNUSEDSIGNAL */
    wire [31:0] sum = a + 32'h3F80_0000;
    /* verilator lint_on UNUSEDSIGNAL */
    wire [31:0] root = {1'b0, sum[31:1]};
    fp_delay #(.WIDTH(32), .LATENCY(LATENCY)) delay (.clk(clk), .d(root), .q(y));
endmodule
