// fp_stage: the registers after stage STAGE of an operator pipelined in STAGES stages
// and run at LATENCY cycles, WIDTH bits wide.
//
// Every pipelined operator of this library divides its logic into STAGES stages of
// about equal depth and ends each with one fp_stage. Stage k gets
// floor(k * LATENCY / STAGES) - floor((k - 1) * LATENCY / STAGES) registers, so the
// registers add up to LATENCY for any LATENCY and are spread evenly: one after every
// stage when LATENCY = STAGES (the design point), some stages merged into one cycle
// when LATENCY < STAGES (LATENCY = 0: combinational), some doubled when it is larger.
// The last stage always gets at least one register when LATENCY > 0, so an operator's
// result comes from a register.
//
// Verilog-2005, synthesizable; part of the rtprof `rtl` crate.
module fp_stage #(
    parameter WIDTH = 32,
    parameter LATENCY = 1,
    parameter STAGES = 1,
    parameter STAGE = 1
) (
    input clk,
    input [WIDTH-1:0] d,
    output [WIDTH-1:0] q
);
    localparam REGS = (STAGE * LATENCY) / STAGES - ((STAGE - 1) * LATENCY) / STAGES;
    fp_delay #(.WIDTH(WIDTH), .LATENCY(REGS)) regs (.clk(clk), .d(d), .q(q));
endmodule
