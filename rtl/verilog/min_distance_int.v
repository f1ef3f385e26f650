// The minimum-distance block with the integer compare (hwmodel's
// MinDistance::IntegerCompare), written by hand: every distance it sees is a
// non-negative float (a root at or beyond the ray's start, or +inf), and those order as
// their bit patterns, so `in_distance[30:0] < kept[30:0]` unsigned decides within the
// cycle the kept registers load (the sign bit is not looked at, as
// hwmodel::float_policy::lt_bits). Compare {compare} cycles + register {register}:
// {total} cycle from a pixel's last primitive to its minimum, and a primitive every
// cycle: the kept value is current when the next distance arrives, so there is neither
// a payload line nor forwarding (`min_distance.v`, the thesis's 3-cycle float compare,
// needs both). The first primitive of a pixel compares against infinity.
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
    reg [W-1:0] kept = {INF, {(W - 32){1'b0}}};
    wire [30:0] against = in_first ? INF[30:0] : kept[W-2 -: 31];
    wire lt = in_distance[30:0] < against;
    reg done = 1'b0;
    always @(posedge clk) begin
        // A pixel whose first primitive misses starts from infinity, as the float block.
        if (in_valid & lt) kept <= payload;
        else if (in_valid & in_first) kept <= {INF, {(W - 32){1'b0}}};
        done <= in_valid & in_last;
    end
    assign {out_0, out_1, out_2, out_3, out_4, out_5} = kept;
    assign out_valid = done;
endmodule
