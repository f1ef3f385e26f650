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
// Datapath: zeros and NaNs are decided first; otherwise differing signs decide, and
// equal signs compare the 31-bit magnitudes (exponent and fraction, an unsigned
// compare), reversed for negative numbers. A combinational core followed by a
// LATENCY-deep register pipeline (fp_delay).
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

    reg r;
    always @* begin
        if (a_nan || b_nan || (a_zero && b_zero))
            r = 1'b0;
        else if (sa != sb)
            // One is negative: a < b iff a is the negative one (not both zero here).
            r = sa;
        else if (sa)
            r = (ma > mb);
        else
            r = (ma < mb);
    end

    fp_delay #(.WIDTH(1), .LATENCY(LATENCY)) delay (.clk(clk), .d(r), .q(lt));
endmodule
