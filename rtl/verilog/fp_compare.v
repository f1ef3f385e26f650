// fp_compare: IEEE-754 single-precision comparison, lt = (a < b).
//
// The ray caster needs one flag: whether a new distance is below the nearest one so far
// (the minimum-distance block keeps b when lt is 0). ALTFP_COMPARE's other flags
// (eq, gt, unordered, ...) have no user in the pipeline, so this module has only `lt`.
//
// Semantics: IEEE 754's compareQuietLess under the library's denormal policy
// (`rtl::float_policy::lt`): subnormal inputs are zeros of the same sign; -0 < +0 is
// false (zeros are equal); any comparison with a NaN is false; -inf and +inf order
// like numbers. The result is one bit, registered LATENCY times.
//
// Datapath, in STAGES = 2 (fp_stage spreads LATENCY registers over them): first the
// flags (zeros, NaNs, signs) and the two 31-bit magnitude comparisons (exponent and
// fraction, unsigned; 9 LUT levels as Yosys maps them, within the 12-level goal, so
// they do without the prefix adder and its fourfold area); then the decision: zeros
// and NaNs first, differing signs, else the magnitudes, reversed for negative numbers.
//
// Verilog-2005, synthesizable; part of the rtprof `rtl` crate.
module fp_compare #(
    parameter LATENCY = 3
) (
    input clk,
    input [31:0] a,
    input [31:0] b,
    output lt
);
    localparam STAGES = 2;

    // Stage 1: flags and magnitude comparisons.
    wire sa = a[31];
    wire sb = b[31];
    wire [7:0] ea = a[30:23];
    wire [7:0] eb = b[30:23];
    wire a_zero = (ea == 8'd0);
    wire b_zero = (eb == 8'd0);
    wire a_nan = (ea == 8'hFF) && (a[22:0] != 23'd0);
    wire b_nan = (eb == 8'hFF) && (b[22:0] != 23'd0);
    // Magnitudes with subnormals flushed.
    wire [30:0] ma = a_zero ? 31'd0 : a[30:0];
    wire [30:0] mb = b_zero ? 31'd0 : b[30:0];
    wire [4:0] s1_d = {a_nan || b_nan || (a_zero && b_zero), sa, sb, ma > mb, ma < mb};
    wire [4:0] s1;
    fp_stage #(.WIDTH(5), .LATENCY(LATENCY), .STAGES(STAGES), .STAGE(1)) st1 (.clk(clk), .d(s1_d), .q(s1));
    wire never, sa2, sb2, a_gt_b, a_lt_b;
    assign {never, sa2, sb2, a_gt_b, a_lt_b} = s1;

    // Stage 2: the decision.
    reg r;
    always @* begin
        if (never)
            r = 1'b0;
        else if (sa2 != sb2)
            // One is negative: a < b iff a is the negative one (not both zero here).
            r = sa2;
        else if (sa2)
            r = a_gt_b;
        else
            r = a_lt_b;
    end
    fp_stage #(.WIDTH(1), .LATENCY(LATENCY), .STAGES(STAGES), .STAGE(2)) st2 (.clk(clk), .d(r), .q(lt));
endmodule
