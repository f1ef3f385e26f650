// vga_controller: the thesis's VGA controller (6.1.8, fig. 28): the sync timing of
// one video mode, the read side of the frame memory, and the pixels out.
//
// Parameters are the mode's timing in pixel clocks (horizontal) and lines (vertical):
// the visible area, front porch, sync pulse and back porch, and each sync's active
// level (0: negative, the pulse is low). The defaults are the industry-standard
// 640 x 480 at 60 Hz mode of VESA's Display Monitor Timing standard (DMT): 25.175 MHz
// pixel clock, lines of 640 + 16 + 96 + 48 = 800 clocks, frames of 480 + 10 + 2 + 33
// = 525 lines, both syncs negative. `rtl::system::vga::VgaTiming` holds the same
// figures for the generator and the testbench's decoder.
//
// A line starts with its visible pixels (column 0 … H_VISIBLE − 1), then the front
// porch, the sync pulse and the back porch; a frame likewise in lines, so the vertical
// sync changes at the start of a line. `column` and `row` are fig. 28's read
// iterators (the counters). The frame memory holds one gray byte per visible pixel,
// row by row, top row first: the order and format of the pipeline's frame-buffer
// writes (fb_addr = row · width + column, fb_data the gray level). The address is a
// running counter (no multiplier): `fb_addr` is the current pixel's, and the memory
// answers on `fb_data` one clock later (a synchronous read, as an M9K's). Gray goes
// out on all three colour channels (the DE2-115's ADV7123 DAC takes 8 bits each) and
// `video_on` drives the DAC's blanking input; outside the visible area RGB is 0.
//
// Every output (`hsync`, `vsync`, `video_on`, RGB) is registered and comes two clocks
// after its counters (the memory read, then the output register), so the timing on the
// pins is the mode's exactly, shifted by two clocks.
//
// Verilog-2005, synthesizable; part of the rtprof `rtl` crate.
module vga_controller #(
    parameter H_VISIBLE = 640,
    parameter H_FRONT = 16,
    parameter H_SYNC = 96,
    parameter H_BACK = 48,
    parameter V_VISIBLE = 480,
    parameter V_FRONT = 10,
    parameter V_SYNC = 2,
    parameter V_BACK = 33,
    parameter HSYNC_ACTIVE = 0,
    parameter VSYNC_ACTIVE = 0,
    // At least log2(H_VISIBLE · V_VISIBLE) (19 for 640 x 480).
    parameter FB_ADDRESS_BITS = 19
) (
    // The pixel clock.
    input clk,
    output [FB_ADDRESS_BITS-1:0] fb_addr,
    input [7:0] fb_data,
    output hsync,
    output vsync,
    output video_on,
    output [7:0] red,
    output [7:0] green,
    output [7:0] blue,
    output [15:0] column,
    output [15:0] row
);
    localparam H_TOTAL = H_VISIBLE + H_FRONT + H_SYNC + H_BACK;
    localparam V_TOTAL = V_VISIBLE + V_FRONT + V_SYNC + V_BACK;
    localparam H_BITS = $clog2(H_TOTAL);
    localparam V_BITS = $clog2(V_TOTAL);
    localparam [H_BITS-1:0] H_LAST = H_TOTAL - 1;
    localparam [V_BITS-1:0] V_LAST = V_TOTAL - 1;
    localparam [H_BITS-1:0] H_SYNC_START = H_VISIBLE + H_FRONT;
    localparam [H_BITS-1:0] H_SYNC_END = H_VISIBLE + H_FRONT + H_SYNC;
    localparam [V_BITS-1:0] V_SYNC_START = V_VISIBLE + V_FRONT;
    localparam [V_BITS-1:0] V_SYNC_END = V_VISIBLE + V_FRONT + V_SYNC;
    localparam [H_BITS-1:0] H_VISIBLE_END = H_VISIBLE;
    localparam [V_BITS-1:0] V_VISIBLE_END = V_VISIBLE;

    // The counters: h across a line, v down a frame.
    reg [H_BITS-1:0] h = 0;
    reg [V_BITS-1:0] v = 0;
    wire line_end = (h == H_LAST);
    always @(posedge clk) begin
        h <= line_end ? {H_BITS{1'b0}} : h + 1'b1;
        if (line_end) v <= (v == V_LAST) ? {V_BITS{1'b0}} : v + 1'b1;
    end
    wire visible = (h < H_VISIBLE_END) && (v < V_VISIBLE_END);
    wire in_hsync = (h >= H_SYNC_START) && (h < H_SYNC_END);
    wire in_vsync = (v >= V_SYNC_START) && (v < V_SYNC_END);

    // The current pixel's address: counts the visible pixels of the frame.
    reg [FB_ADDRESS_BITS-1:0] address = 0;
    always @(posedge clk) begin
        if (line_end && v == V_LAST) address <= 0;
        else if (visible) address <= address + 1'b1;
    end
    assign fb_addr = address;

    // Stage 1: beside the memory read.
    reg visible_1 = 1'b0, hsync_1 = 1'b0, vsync_1 = 1'b0;
    always @(posedge clk) begin
        visible_1 <= visible;
        hsync_1 <= in_hsync;
        vsync_1 <= in_vsync;
    end

    // Stage 2: the output registers (the sync levels of an idle line at power-up).
    reg video_r = 1'b0;
    reg hsync_r = !HSYNC_ACTIVE, vsync_r = !VSYNC_ACTIVE;
    reg [7:0] gray_r = 8'd0;
    always @(posedge clk) begin
        video_r <= visible_1;
        hsync_r <= hsync_1 ? (HSYNC_ACTIVE != 0) : (HSYNC_ACTIVE == 0);
        vsync_r <= vsync_1 ? (VSYNC_ACTIVE != 0) : (VSYNC_ACTIVE == 0);
        gray_r <= visible_1 ? fb_data : 8'd0;
    end

    assign hsync = hsync_r;
    assign vsync = vsync_r;
    assign video_on = video_r;
    assign red = gray_r;
    assign green = gray_r;
    assign blue = gray_r;
    assign column = {{(16 - H_BITS) {1'b0}}, h};
    assign row = {{(16 - V_BITS) {1'b0}}, v};
endmodule
