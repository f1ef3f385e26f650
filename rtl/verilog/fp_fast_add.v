// fp_fast_add: a W-bit adder with logarithmic depth, s = a + b + ci, co its carry out;
// with NEG_B = 1, s = a + ~b + ci.
//
// The pipelined operators' wide additions, subtractions and comparisons (a - b is
// a + ~b + 1 with NEG_B = 1; its carry out is 1 when a >= b). The inversion is a
// parameter, not the caller's `~b`, so that it lives in this module: with the
// hierarchy kept (rtl::synth), an inverter at a module port is a LUT level of its own
// that ABC cannot fold into the first prefix level. A Kogge-Stone parallel-prefix adder:
// the (generate, propagate) pairs of every span of 2^l bits, l = 0 .. ceil(log2(W+1)),
// each level one 3-input function per bit, so a 26-bit sum is 5 LUT levels where a
// `+` is a ripple of about 17 (Yosys's synth_intel has no carry chains).
//
// The prefix levels carry (* keep *): without it ABC's area-oriented rewriting (dc2,
// in Yosys's default `abc -lut 4` script) folds the tree back into a ripple, which is
// smaller and three times as deep.
//
// With RTPROF_BEHAVIOURAL_ARITHMETIC defined (the whole-pipeline simulation, rtl::sim)
// the sum is a plain `+`: the same function, and a Verilator model of the generated
// design that builds in minutes instead of half an hour. The operator tests
// (rtl/tests/operators.rs) simulate the prefix tree itself, bit-exact on every input.
//
// Verilog-2005, synthesizable; part of the rtprof `rtl` crate.
module fp_fast_add #(
    parameter W = 26,
    parameter NEG_B = 0
) (
    input [W-1:0] a,
    input [W-1:0] b,
    input ci,
    output [W-1:0] s,
    output co
);
    wire [W-1:0] bb = NEG_B ? ~b : b;
`ifdef RTPROF_BEHAVIOURAL_ARITHMETIC
    assign {co, s} = {1'b0, a} + {1'b0, bb} + {{W{1'b0}}, ci};
`else
    localparam LEVELS = $clog2(W + 1);
    genvar l, i;
    generate
        for (l = 0; l <= LEVELS; l = l + 1) begin : level
            // Bit 0 of every level is the carry in; bit i + 1 spans bits <= i.
            /* verilator lint_off UNUSEDSIGNAL */
            (* keep *) wire [W:0] g;
            (* keep *) wire [W:0] p;
            /* verilator lint_on UNUSEDSIGNAL */
            if (l == 0) begin : init
                assign g = {a & bb, ci};
                assign p = {a ^ bb, 1'b0};
            end else begin : span
                for (i = 0; i <= W; i = i + 1) begin : bits
                    if (i >= (1 << (l - 1))) begin : join_
                        assign g[i] = level[l-1].g[i]
                            | (level[l-1].p[i] & level[l-1].g[i-(1<<(l-1))]);
                        assign p[i] = level[l-1].p[i] & level[l-1].p[i-(1<<(l-1))];
                    end else begin : keep_
                        assign g[i] = level[l-1].g[i];
                        assign p[i] = level[l-1].p[i];
                    end
                end
            end
        end
    endgenerate
    // The carry into bit i is the generate of the span below it.
    assign s = level[0].p[W:1] ^ level[LEVELS].g[W-1:0];
    assign co = level[LEVELS].g[W];
`endif
endmodule
