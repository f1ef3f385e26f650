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
// 255. A combinational core followed by a LATENCY-deep register pipeline (fp_delay).
//
// Verilog-2005, synthesizable; part of the rtprof `rtl` crate.
module fp_to_u8 #(
    parameter LATENCY = 6
) (
    input clk,
    input [31:0] a,
    output [7:0] y
);
    reg [7:0] r;

    reg sa, a_nan;
    reg [7:0] ea;
    reg [4:0] shift;
    // Only twice[8:0] matters: a >= 256 saturates before it is looked at.
    /* verilator lint_off UNUSEDSIGNAL */
    reg [23:0] twice;
    /* verilator lint_on UNUSEDSIGNAL */
    reg [8:0] sum;

    always @* begin
        sa = a[31];
        ea = a[30:23];
        a_nan = (ea == 8'hFF) && (a[22:0] != 23'd0);

        // e in [126, 134]: shift = 149 - e in [15, 23], computed on the exponent's
        // low five bits (149 - e = 21 - e modulo 32); twice = floor(2 a) < 512.
        shift = 5'd21 - ea[4:0];
        twice = {1'b1, a[22:0]} >> shift;
        sum = {1'b0, twice[8:1]} + {8'd0, twice[0]};

        if (a_nan || sa || ea < 8'd126)
            r = 8'd0;  // NaN, negative, zero, subnormal or below one half
        else if (ea > 8'd134 || sum[8])
            r = 8'hFF;  // 255.5 or more, +inf: saturate
        else
            r = sum[7:0];
    end

    fp_delay #(.WIDTH(8), .LATENCY(LATENCY)) delay (.clk(clk), .d(r), .q(y));
endmodule
