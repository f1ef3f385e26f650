// fp_register: a 32-bit word delayed by LATENCY clock cycles.
//
// The pipeline's balancing registers (hwmodel operator `register`, latency 1 per
// stage): a value that must wait for a slower parallel branch goes through one of
// these. LATENCY comes from the operator library like every other operator's; a delay
// line of n cycles is one fp_register with LATENCY = n.
//
// Verilog-2005, synthesizable; part of the rtprof `rtl` crate.
module fp_register #(
    parameter LATENCY = 1
) (
    input clk,
    input [31:0] a,
    output [31:0] y
);
    fp_delay #(.WIDTH(32), .LATENCY(LATENCY)) delay (.clk(clk), .d(a), .q(y));
endmodule
