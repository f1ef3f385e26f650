// The minimum-distance block (thesis fig. 25), written by hand: compare the incoming
// distance with the kept one ({compare} cycles) and load distance, P, m and address into the
// registers ({register} cycle): {total} cycles from a pixel's last primitive to its minimum.
// Primitives arrive every 3 cycles, so the next compare starts in the cycle the previous
// result appears: the kept value is forwarded to it (`kept_next`). The first primitive
// of a pixel compares against infinity. The payload waits beside the compare: the model
// holds the inputs 3 cycles instead (the 3n pacing), these are its registers.
module min_distance (
    input clk,
    input in_valid,
    input in_first,
    input in_last,
    input [31:0] in_distance,
    input [31:0] in_P_x,
    input [31:0] in_P_y,
    input [31:0] in_P_z,
    input [31:0] in_m,
    input [{ab}:0] in_address,
    output [31:0] out_0,
    output [31:0] out_1,
    output [31:0] out_2,
    output [31:0] out_3,
    output [31:0] out_4,
    output [{ab}:0] out_5,
    output out_valid
);
    localparam W = 5 * 32 + {a};
    localparam [31:0] INF = 32'h7F800000;
    wire [W-1:0] payload = {in_distance, in_P_x, in_P_y, in_P_z, in_m, in_address};
    wire [W-1:0] payload_d;
    wire [2:0] flags_d; // valid, first, last
    fp_delay #(.WIDTH(W), .LATENCY({compare})) payload_line (.clk(clk), .d(payload), .q(payload_d));
    fp_delay #(.WIDTH(3), .LATENCY({compare})) flag_line (.clk(clk), .d({in_valid, in_first, in_last}), .q(flags_d));
    reg [W-1:0] kept = {INF, {(W - 32){1'b0}}};
    wire lt;
    wire [W-1:0] kept_next = (flags_d[2] & lt) ? payload_d
        : (flags_d[2] & flags_d[1]) ? {INF, {(W - 32){1'b0}}} : kept;
    wire [31:0] against = in_first ? INF : kept_next[W-1 -: 32];
    fp_compare #(.LATENCY({compare})) closer (.clk(clk), .a(in_distance), .b(against), .lt(lt));
    reg done = 1'b0;
    always @(posedge clk) begin
        kept <= kept_next;
        done <= flags_d[2] & flags_d[0];
    end
    assign {out_0, out_1, out_2, out_3, out_4, out_5} = kept;
    assign out_valid = done;
endmodule
