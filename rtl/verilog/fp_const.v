// fp_const: a 32-bit constant word, y = VALUE.
//
// The pipeline's constants (1.0 in the bit trick, 0.5 in the solver, the background
// colour ...) as a module, so that generated RTL instantiates every value source the
// same way. A constant has no timing: no clock, no LATENCY (it is valid in every
// cycle, so it never needs a delay line to line up with other operands).
//
// Verilog-2005, synthesizable; part of the rtprof `rtl` crate.
module fp_const #(
    parameter [31:0] VALUE = 32'h0000_0000
) (
    output [31:0] y
);
    assign y = VALUE;
endmodule
