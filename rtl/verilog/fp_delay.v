// fp_delay: a LATENCY-deep register delay line, WIDTH bits wide.
//
// The timing primitive of every operator in this library: each operator is a
// combinational core followed by one fp_delay, so its result appears exactly LATENCY
// clock cycles after its inputs (LATENCY = 0: a wire, the operator is combinational).
// The registers have no reset and no enable: the pipeline streams one input per clock
// and results of the first LATENCY cycles are don't-cares. Synthesis tools may retime
// the registers into the core (Quartus register retiming, or Yosys with -retime); the
// latency stays the same.
//
// Verilog-2005, synthesizable; part of the rtprof `rtl` crate.
module fp_delay #(
    parameter WIDTH = 32,
    parameter LATENCY = 1
) (
    // Unused when LATENCY = 0.
    /* verilator lint_off UNUSEDSIGNAL */
    input clk,
    /* verilator lint_on UNUSEDSIGNAL */
    input [WIDTH-1:0] d,
    output [WIDTH-1:0] q
);
    generate
        if (LATENCY == 0) begin : g_wire
            assign q = d;
        end else if (LATENCY == 1) begin : g_one
            reg [WIDTH-1:0] r;
            always @(posedge clk) r <= d;
            assign q = r;
        end else begin : g_chain
            // Stage k (0 = newest) sits in bits [WIDTH*(k+1)-1 : WIDTH*k].
            reg [WIDTH*LATENCY-1:0] r;
            always @(posedge clk) r <= {r[WIDTH*(LATENCY-1)-1:0], d};
            assign q = r[WIDTH*LATENCY-1 -: WIDTH];
        end
    endgenerate
endmodule
