// fp_to_u8: IEEE-754 single precision to an unsigned 8-bit integer, y = (u8) round(a).
//
// The pipeline's output conversion (hwmodel operator `convert`, ALTFP_CONVERT): the
// pixel's gray value, already scaled to 0..255, to the 8-bit word written to the frame
// buffer. `rtl::float_policy::to_u8` is the reference.
//
// Semantics: round to nearest, ties away from zero (Rust's `f32::round`: 0.5 -> 1,
// 127.5 -> 128, 254.5 -> 255), then saturate to 0..255: values of 255.5 and more and
// +inf give 255; negative values (-0.4 rounds to -0, -0.5 to -1), zeros, subnormals
// (flushed like every operator's inputs) and NaNs give 0.
//
// Datapath: for a positive normal a = 1.f * 2^(e - 127) below 256 (e <= 134), the
// significand {1, f} shifted right by 149 - e (a shift of at most 23 bits; e < 126 is
// below one half and gives 0) is floor(2 a): its top bits the integer part and its
// lowest bit the half, which rounds up. A sum of 256 (a in [255.5, 256)) saturates to
// 255. STAGES = 2 (fp_stage spreads LATENCY registers over them): the flags and the
// shift, then the rounding and saturation.
//
// Verilog-2005, synthesizable; part of the rtprof `rtl` crate.
module fp_to_u8 #(
    parameter LATENCY = 6
) (
    input clk,
    input [31:0] a,
    output [7:0] y
);
    localparam STAGES = 2;

    // Stage 1: flags and floor(2 a).
    wire sa = a[31];
    wire [7:0] ea = a[30:23];
    wire a_nan = (ea == 8'hFF) && (a[22:0] != 23'd0);
    // e in [126, 134]: shift = 149 - e in [15, 23], computed on the exponent's low five
    // bits (149 - e = 21 - e modulo 32); twice = floor(2 a) < 512.
    wire [4:0] shift = 5'd21 - ea[4:0];
    // Only twice[8:0] matters: a >= 256 saturates before it is looked at.
    /* verilator lint_off UNUSEDSIGNAL */
    wire [23:0] twice = {1'b1, a[22:0]} >> shift;
    /* verilator lint_on UNUSEDSIGNAL */
    // Zero: NaN, negative, zero, subnormal or below one half; saturate: 256 or more.
    wire [10:0] s1_d = {a_nan || sa || ea < 8'd126, ea > 8'd134, twice[8:0]};
    wire [10:0] s1;
    fp_stage #(.WIDTH(11), .LATENCY(LATENCY), .STAGES(STAGES), .STAGE(1)) st1 (.clk(clk), .d(s1_d), .q(s1));
    wire zero2, big2;
    wire [8:0] twice2;
    assign {zero2, big2, twice2} = s1;

    // Stage 2: round half up, saturate.
    wire [8:0] sum = {1'b0, twice2[8:1]} + {8'd0, twice2[0]};
    wire [7:0] r = zero2 ? 8'd0 : (big2 || sum[8]) ? 8'hFF : sum[7:0];
    fp_stage #(.WIDTH(8), .LATENCY(LATENCY), .STAGES(STAGES), .STAGE(2)) st2 (.clk(clk), .d(r), .q(y));
endmodule
