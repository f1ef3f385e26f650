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
// Datapath: absolute value, a leading-zero count (a `for` loop), a left shift that
// puts the leading one at bit 31, rounding at bit 8 with a guard and a sticky bit. A
// combinational core followed by a LATENCY-deep register pipeline (fp_delay).
//
// Verilog-2005, synthesizable; part of the rtprof `rtl` crate.
module fp_from_int #(
    parameter LATENCY = 6
) (
    input clk,
    input [31:0] a,
    output [31:0] y
);
    reg [31:0] r;

    reg s, found, g, st, up;
    reg [31:0] mag, norm;
    reg [5:0] lz;
    // mr[23] is the hidden one: it is not stored.
    /* verilator lint_off UNUSEDSIGNAL */
    reg [24:0] mr;
    /* verilator lint_on UNUSEDSIGNAL */
    reg [7:0] e;
    integer i;

    always @* begin
        s = a[31];
        mag = s ? (~a + 32'd1) : a;
        lz = 6'd0;
        found = 1'b0;
        for (i = 31; i >= 0; i = i - 1) begin
            if (!found) begin
                if (mag[i]) found = 1'b1;
                else lz = lz + 6'd1;
            end
        end
        norm = mag << lz;
        // Leading one at bit 31: value = norm * 2^(-lz) with 2^31 weight, exponent
        // 31 - lz, biased 158 - lz.
        e = 8'd158 - {2'b00, lz};
        g = norm[7];
        st = |norm[6:0];
        up = g & (st | norm[8]);
        mr = {1'b0, norm[31:8]} + {24'd0, up};
        if (mr[24]) begin
            mr = {2'b01, 23'd0};
            e = e + 8'd1;
        end
        if (a == 32'd0)
            r = 32'd0;
        else
            r = {s, e, mr[22:0]};
    end

    fp_delay #(.WIDTH(32), .LATENCY(LATENCY)) delay (.clk(clk), .d(r), .q(y));
endmodule
