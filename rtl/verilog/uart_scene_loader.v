// uart_scene_loader: the scene block's serial loader (thesis 6.1.1: "a block that
// obtains the scene over the serial port and stores it in memory"). It receives a
// scene upload through uart_rx and writes the scene memory through the pipeline top's
// loader port, word by word, and holds the frame set-up registers the top reads.
//
// The stream (written by `rtl::system::uart::scene_stream`, where the framing is
// documented; every word little-endian, least significant byte first):
//
//   'R' 'T' 'S' 'C'                      magic (the loader hunts for it)
//   H0   width | height << 16            must equal WIDTH and HEIGHT (the frame memory)
//   H1   per_unit | prim_count << 16     1 <= prim_count <= 2^DEPTH_BITS
//   H2   background | fields << 8        fields must equal FIELDS; bits 16-31: 0
//   H3 … H23                             the frame vectors, x y z each (`vectors`)
//   M0 … M(prim_count·FIELDS − 1)        the memory words, primitive by primitive
//   CRC                                  CRC-32 of H0 … the last M (not the magic)
//
// The CRC is the one of zlib, PNG and Ethernet (reflected polynomial 0xEDB88320,
// initial value and final XOR 0xFFFFFFFF), updated one byte per received byte.
// Memory words are written as they arrive (`load_we` for one cycle, `load_addr` the
// primitive, `load_field` its word); `loaded` rises when the CRC matches and stays
// high: the pipeline's start. A header the design cannot hold, a framing error or a
// wrong CRC raises `error` and the loader hunts for the magic again (`error` falls at
// the next magic). After `loaded` the loader ignores the line: the generated top
// renders one frame per configuration.
//
// Verilog-2005, synthesizable; part of the rtprof `rtl` crate.
module uart_scene_loader #(
    parameter CLKS_PER_BIT = 434,
    // The top's loader address width (hwmodel's ADDRESS_BITS).
    parameter ADDRESS_BITS = 13,
    // The scene memory holds 2^DEPTH_BITS primitives.
    parameter DEPTH_BITS = 6,
    // Words per primitive the design stores (9, or 14 with rsqrt-free shading).
    parameter FIELDS = 9,
    parameter WIDTH = 640,
    parameter HEIGHT = 480
) (
    input clk,
    input rx,
    output load_we,
    output [ADDRESS_BITS-1:0] load_addr,
    output [3:0] load_field,
    output [31:0] load_data,
    output [15:0] width,
    output [15:0] height,
    output [15:0] per_unit,
    output [15:0] prim_count,
    output [7:0] background,
    // H3 … H23: word k of the vectors at bits 32k … 32k + 31.
    output [21*32-1:0] vectors,
    output loaded,
    output error
);
    localparam [31:0] MAGIC = 32'h52545343;  // "RTSC", first byte most significant
    localparam HEADER_WORDS = 24;
    localparam MAX_PRIMITIVES = 1 << DEPTH_BITS;
    localparam HUNT = 3'd0, HEADER = 3'd1, MEMORY = 3'd2, CHECK = 3'd3, DONE = 3'd4;

    wire rx_valid, rx_error;
    wire [7:0] rx_data;
    uart_rx #(.CLKS_PER_BIT(CLKS_PER_BIT)) receiver (
        .clk(clk), .rx(rx), .valid(rx_valid), .data(rx_data), .frame_error(rx_error)
    );

    // CRC-32, one byte at a time (eight shift-and-XOR steps: an XOR network, no carry).
    function [31:0] crc32_byte;
        input [31:0] crc;
        input [7:0] byte_in;
        integer i;
        reg [31:0] c;
        begin
            c = crc ^ {24'd0, byte_in};
            for (i = 0; i < 8; i = i + 1) c = c[0] ? ((c >> 1) ^ 32'hEDB88320) : (c >> 1);
            crc32_byte = c;
        end
    endfunction

    reg [2:0] state = HUNT;
    reg [23:0] tail = 24'd0;  // the three bytes before this one, while hunting
    reg [23:0] word = 24'd0;  // the word's bytes so far, the last received highest
    reg [1:0] byte_count = 2'd0;
    reg [4:0] header_index = 5'd0;
    reg [31:0] crc = 32'hFFFFFFFF;
    reg [15:0] prim = 16'd0;
    reg [3:0] field = 4'd0;
    wire [31:0] next_word = {rx_data, word};
    wire word_done = byte_count == 2'd3;

    reg we_r = 1'b0;
    reg [ADDRESS_BITS-1:0] addr_r = 0;
    reg [3:0] field_r = 4'd0;
    reg [31:0] data_r = 32'd0;
    reg [15:0] width_r = 16'd0, height_r = 16'd0, per_unit_r = 16'd0, prim_count_r = 16'd0;
    reg [7:0] background_r = 8'd0;
    reg [31:0] vector_r [0:20];
    reg loaded_r = 1'b0, error_r = 1'b0;

    integer v;
    initial for (v = 0; v < 21; v = v + 1) vector_r[v] = 32'd0;

    always @(posedge clk) begin
        we_r <= 1'b0;
        if (rx_error && (state == HEADER || state == MEMORY || state == CHECK)) begin
            error_r <= 1'b1;
            state <= HUNT;
        end else if (rx_valid) begin
            case (state)
                HUNT: begin
                    tail <= {tail[15:0], rx_data};
                    if ({tail, rx_data} == MAGIC) begin
                        state <= HEADER;
                        tail <= 24'd0;
                        error_r <= 1'b0;
                        byte_count <= 2'd0;
                        header_index <= 5'd0;
                        crc <= 32'hFFFFFFFF;
                    end
                end
                HEADER, MEMORY: begin
                    word <= next_word[31:8];
                    byte_count <= byte_count + 2'd1;
                    crc <= crc32_byte(crc, rx_data);
                    if (word_done && state == HEADER) begin
                        header_index <= header_index + 5'd1;
                        case (header_index)
                            5'd0: begin
                                width_r <= next_word[15:0];
                                height_r <= next_word[31:16];
                            end
                            5'd1: begin
                                per_unit_r <= next_word[15:0];
                                prim_count_r <= next_word[31:16];
                            end
                            5'd2: begin
                                background_r <= next_word[7:0];
                                if (width_r != WIDTH || height_r != HEIGHT
                                    || next_word[15:8] != FIELDS || next_word[31:16] != 16'd0
                                    || prim_count_r == 16'd0 || prim_count_r > MAX_PRIMITIVES
                                    || per_unit_r == 16'd0) begin
                                    error_r <= 1'b1;
                                    state <= HUNT;
                                end
                            end
                            default: vector_r[header_index - 5'd3] <= next_word;
                        endcase
                        if (header_index == HEADER_WORDS - 1) begin
                            state <= MEMORY;
                            prim <= 16'd0;
                            field <= 4'd0;
                        end
                    end
                    if (word_done && state == MEMORY) begin
                        we_r <= 1'b1;
                        addr_r <= prim[ADDRESS_BITS-1:0];
                        field_r <= field;
                        data_r <= next_word;
                        if (field == FIELDS - 1) begin
                            field <= 4'd0;
                            prim <= prim + 16'd1;
                            if (prim == prim_count_r - 16'd1) state <= CHECK;
                        end else field <= field + 4'd1;
                    end
                end
                CHECK: begin
                    word <= next_word[31:8];
                    byte_count <= byte_count + 2'd1;
                    if (word_done) begin
                        if (next_word == ~crc) begin
                            loaded_r <= 1'b1;
                            state <= DONE;
                        end else begin
                            error_r <= 1'b1;
                            state <= HUNT;
                        end
                    end
                end
                default: ;  // DONE: one scene per configuration
            endcase
        end
    end

    assign load_we = we_r;
    assign load_addr = addr_r;
    assign load_field = field_r;
    assign load_data = data_r;
    assign width = width_r;
    assign height = height_r;
    assign per_unit = per_unit_r;
    assign prim_count = prim_count_r;
    assign background = background_r;
    genvar g;
    generate
        for (g = 0; g < 21; g = g + 1) begin : g_vectors
            assign vectors[32*g +: 32] = vector_r[g];
        end
    endgenerate
    assign loaded = loaded_r;
    assign error = error_r;
endmodule
