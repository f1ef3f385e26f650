// fp_lzc: the leading zeros of a 2^N-bit word, lz = 2^N when x = 0.
//
// The normalisations of the pipelined operators (fp_add_sub, fp_from_int). A tree:
// each node of level l covers 2^l bits and knows whether they are all zero and, if
// not, their leading zeros (l bits); a parent takes its upper child's count, or 2^(l-1)
// plus its lower child's when the upper one is all zero. N + 1 LUT levels or so, where
// a count written as a loop is a ripple through all the bits.
//
// Verilog-2005, synthesizable; part of the rtprof `rtl` crate.
module fp_lzc #(
    parameter N = 5
) (
    input [(1<<N)-1:0] x,
    output [N:0] lz
);
    genvar l, j;
    generate
        for (l = 1; l <= N; l = l + 1) begin : level
            localparam NODES = (1 << N) >> l;
            wire [NODES-1:0] z;
            wire [NODES*l-1:0] c;
            for (j = 0; j < NODES; j = j + 1) begin : node
                if (l == 1) begin : pair
                    assign z[j] = ~x[2*j+1] & ~x[2*j];
                    assign c[j] = ~x[2*j+1];
                end else begin : join_
                    wire z_hi = level[l-1].z[2*j+1];
                    wire z_lo = level[l-1].z[2*j];
                    wire [l-2:0] c_hi = level[l-1].c[(2*j+1)*(l-1) +: (l-1)];
                    wire [l-2:0] c_lo = level[l-1].c[(2*j)*(l-1) +: (l-1)];
                    assign z[j] = z_hi & z_lo;
                    assign c[j*l +: l] = z_hi ? {1'b1, c_lo} : {1'b0, c_hi};
                end
            end
        end
    endgenerate
    assign lz = level[N].z[0] ? (1 << N) : {1'b0, level[N].c};
endmodule
