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
// Datapath: the 24 x 24-bit significand product (fp_mul_array below; the `*` maps to
// the embedded multipliers), normalised by at most one bit, rounded with guard and
// sticky bits. A combinational core followed by a LATENCY-deep register pipeline
// (fp_delay).
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
    reg [31:0] r;

    reg s, a_zero, b_zero, a_inf, b_inf, a_nan, b_nan, g, st, up;
    reg [7:0] ea, eb;
    reg [22:0] fa, fb;
    wire [47:0] p;
    reg [23:0] m;
    // mr[23] is the hidden one: it is not stored.
    /* verilator lint_off UNUSEDSIGNAL */
    reg [24:0] mr;
    /* verilator lint_on UNUSEDSIGNAL */
    integer e;

    fp_mul_array product (.a({1'b1, a[22:0]}), .b({1'b1, b[22:0]}), .p(p));

    always @* begin
        s = a[31] ^ b[31];
        ea = a[30:23];
        eb = b[30:23];
        fa = a[22:0];
        fb = b[22:0];
        a_zero = (ea == 8'd0);
        b_zero = (eb == 8'd0);
        a_inf = (ea == 8'hFF) && (fa == 23'd0);
        b_inf = (eb == 8'hFF) && (fb == 23'd0);
        a_nan = (ea == 8'hFF) && (fa != 23'd0);
        b_nan = (eb == 8'hFF) && (fb != 23'd0);

        e = {24'd0, ea} + {24'd0, eb} - 127;
        if (p[47]) begin
            m = p[47:24];
            g = p[23];
            st = |p[22:0];
            e = e + 1;
        end else begin
            m = p[46:23];
            g = p[22];
            st = |p[21:0];
        end
        up = g & (st | m[0]);
        mr = {1'b0, m} + {24'd0, up};
        if (mr[24]) begin
            mr = {2'b01, 23'd0};
            e = e + 1;
        end

        if (a_nan || b_nan || (a_inf && b_zero) || (b_inf && a_zero))
            r = 32'h7FC0_0000;
        else if (a_inf || b_inf)
            r = {s, 8'hFF, 23'd0};
        else if (a_zero || b_zero)
            r = {s, 31'd0};
        else if (e >= 255)
            r = {s, 8'hFF, 23'd0};
        else if (e <= 0)
            r = {s, 31'd0};  // below the smallest normal after rounding: flush
        else
            r = {s, e[7:0], mr[22:0]};
    end

    fp_delay #(.WIDTH(32), .LATENCY(LATENCY)) delay (.clk(clk), .d(r), .q(y));
endmodule

// fp_mul_array: the unsigned 24 x 24-bit significand product of fp_mul, p = a * b,
// combinational. A module of its own only so that synthesis keeps it apart: the
// Yosys reports of `rtl::synth` count the logic of its instances as multiplier logic
// (Quartus maps it to the embedded 9 x 9 / 18 x 18 multipliers; Yosys's synth_intel
// builds it from LUTs).
/* verilator lint_off DECLFILENAME */
module fp_mul_array (
    input [23:0] a,
    input [23:0] b,
    output [47:0] p
);
    assign p = {24'd0, a} * {24'd0, b};
endmodule
/* verilator lint_on DECLFILENAME */
