// fp_select: the 32-bit 2:1 multiplexer, y = sel ? b : a.
//
// The pipeline's selects (hwmodel operator `mux`, combinational in the Cyclone IV E
// library, LATENCY = 0): the nearer of two hits, a colour or the background. The
// words are passed bit for bit (no flushing, NaNs keep their payload). With LATENCY > 0
// the selected word is registered LATENCY times.
//
// Verilog-2005, synthesizable; part of the rtprof `rtl` crate.
module fp_select #(
    parameter LATENCY = 0
) (
    input clk,
    input sel,
    input [31:0] a,
    input [31:0] b,
    output [31:0] y
);
    wire [31:0] picked = sel ? b : a;
    fp_delay #(.WIDTH(32), .LATENCY(LATENCY)) delay (.clk(clk), .d(picked), .q(y));
endmodule
