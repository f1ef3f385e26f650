// uart_rx: an 8N1 serial receiver (one start bit, 8 data bits least significant
// first, no parity, one stop bit), CLKS_PER_BIT clock cycles per bit.
//
// The line idles high. The input passes two flip-flops first (it comes from another
// clock domain: the USB-serial bridge). A falling edge starts a byte; half a bit
// later the start bit is sampled again (still low, else it was a glitch and the
// receiver waits again), then every CLKS_PER_BIT cycles one data bit, each in the
// middle of its bit time, and the stop bit. Mid-bit sampling tolerates a clock error
// between sender and receiver of up to about half a bit over the 9.5 bits from the
// start edge to the stop bit's middle (±5 %, less the edge's one-cycle uncertainty).
//
// Outputs, for one cycle: `valid` with `data` when the stop bit is high, else
// `frame_error` (a break or a wrong bit rate); after a framing error the receiver
// waits for the line to return high before it looks for the next start edge.
//
// At the thesis's 50 MHz clock, CLKS_PER_BIT = 434 is 115,200 baud (0.01 % fast).
//
// Verilog-2005, synthesizable; part of the rtprof `rtl` crate.
module uart_rx #(
    parameter CLKS_PER_BIT = 434
) (
    input clk,
    input rx,
    output valid,
    output [7:0] data,
    output frame_error
);
    localparam COUNT_BITS = $clog2(CLKS_PER_BIT + 1);
    localparam [COUNT_BITS-1:0] HALF = CLKS_PER_BIT / 2 - 1;
    localparam [COUNT_BITS-1:0] FULL = CLKS_PER_BIT - 1;
    localparam IDLE = 3'd0, START = 3'd1, DATA = 3'd2, STOP = 3'd3, WAIT_HIGH = 3'd4;

    // Two synchronizing flip-flops; the line idles high.
    reg rx_meta = 1'b1, rx_sync = 1'b1;
    always @(posedge clk) begin
        rx_meta <= rx;
        rx_sync <= rx_meta;
    end

    reg [2:0] state = IDLE;
    reg [COUNT_BITS-1:0] count = 0;
    reg [2:0] bit_index = 3'd0;
    reg [7:0] shift = 8'd0;
    reg valid_r = 1'b0, error_r = 1'b0;

    always @(posedge clk) begin
        valid_r <= 1'b0;
        error_r <= 1'b0;
        case (state)
            IDLE: begin
                count <= 0;
                if (!rx_sync) state <= START;
            end
            START: begin
                // Half a bit after the edge: the middle of the start bit.
                if (count == HALF) begin
                    count <= 0;
                    bit_index <= 3'd0;
                    state <= rx_sync ? IDLE : DATA;
                end else count <= count + 1'b1;
            end
            DATA: begin
                if (count == FULL) begin
                    count <= 0;
                    shift <= {rx_sync, shift[7:1]};
                    bit_index <= bit_index + 3'd1;
                    if (bit_index == 3'd7) state <= STOP;
                end else count <= count + 1'b1;
            end
            STOP: begin
                if (count == FULL) begin
                    count <= 0;
                    if (rx_sync) begin
                        valid_r <= 1'b1;
                        state <= IDLE;
                    end else begin
                        error_r <= 1'b1;
                        state <= WAIT_HIGH;
                    end
                end else count <= count + 1'b1;
            end
            default: begin
                // WAIT_HIGH: after a framing error, until the line idles again.
                if (rx_sync) state <= IDLE;
            end
        endcase
    end

    assign valid = valid_r;
    assign data = shift;
    assign frame_error = error_r;
endmodule
