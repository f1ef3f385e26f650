// vga_frame_buffer: the thesis's frame memory (6.1.9): one gray byte per pixel,
// WORDS = width · height of them, row by row, top row first.
//
// Two ports in two clock domains, as an M9K's simple dual-port mode has them: the
// pipeline writes on its clock (the top's fb_we / fb_addr / fb_data, one pixel per
// write in issue order; writes past the end are dropped), the VGA controller reads on
// the pixel clock, the word one clock after its address. Nothing synchronises the two:
// the display shows the memory as it is, the picture filling in while it renders.
// 640 x 480 bytes are 2,457,600 bits: 300 M9K blocks of the EP4CE115's 432.
//
// Verilog-2005, synthesizable; part of the rtprof `rtl` crate.
module vga_frame_buffer #(
    parameter WORDS = 640 * 480,
    parameter ADDRESS_BITS = 19
) (
    input write_clk,
    input we,
    input [31:0] write_addr,
    input [7:0] write_data,
    input read_clk,
    input [ADDRESS_BITS-1:0] read_addr,
    output [7:0] read_data
);
    reg [7:0] memory [0:WORDS-1];
    always @(posedge write_clk)
        if (we && write_addr < WORDS) memory[write_addr[ADDRESS_BITS-1:0]] <= write_data;
    reg [7:0] read_r = 8'd0;
    always @(posedge read_clk) read_r <= memory[read_addr];
    assign read_data = read_r;
endmodule
