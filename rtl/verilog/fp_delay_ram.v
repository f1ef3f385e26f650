// A delay line in memory: q is d delayed by DELAY cycles (DELAY >= 3), held in a
// circular buffer of DELAY - 1 words with a registered read (Quartus's altshift_taps,
// an M9K, for the long lines the operator library puts in memory). Each cycle the
// word written DELAY - 1 cycles ago is read (read before write at one address) and
// replaced; the read register adds the last cycle.
module fp_delay_ram #(
    parameter WIDTH = 32,
    parameter DELAY = 16
) (
    input clk,
    input [WIDTH-1:0] d,
    output [WIDTH-1:0] q
);
    localparam DEPTH = DELAY - 1;
    localparam PTR_BITS = $clog2(DEPTH);
    reg [WIDTH-1:0] mem [0:DEPTH-1];
    reg [PTR_BITS-1:0] ptr = 0;
    reg [WIDTH-1:0] r;
    always @(posedge clk) begin
        r <= mem[ptr];
        mem[ptr] <= d;
        ptr <= (ptr == DEPTH - 1) ? 0 : ptr + 1'b1;
    end
    assign q = r;
endmodule
