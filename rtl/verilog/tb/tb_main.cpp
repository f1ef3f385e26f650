// Verilator testbench of one RTL operator (rtl/tests/operators.rs).
//
// The model's top is `tb_top`, a wrapper the test generates around the operator with
// the uniform ports clk, a, b, c (32 bits each; c carries control inputs such as
// fp_add_sub's `sub`) and y (32 bits). The testbench streams one input triple per clock
// cycle and records y once per cycle, just before the rising edge, so that the result
// for input k is expected in record k + LATENCY (the inputs of cycle k reach the
// combinational core immediately, and each register stage adds one cycle).
//
// Usage: tb <inputs.bin> <outputs.bin> <extra_cycles>
//   inputs.bin: little-endian u32 triples (a, b, c), one per cycle;
//   outputs.bin: little-endian u32 y, one per cycle, for n + extra_cycles cycles
//   (the last extra_cycles cycles repeat the final input triple).
#include "Vtb_top.h"
#include "verilated.h"

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <vector>

static std::vector<uint32_t> read_words(const char* path) {
    std::vector<uint32_t> words;
    FILE* f = std::fopen(path, "rb");
    if (!f) {
        std::perror(path);
        std::exit(2);
    }
    uint8_t buf[4];
    while (std::fread(buf, 1, 4, f) == 4) {
        words.push_back(uint32_t(buf[0]) | uint32_t(buf[1]) << 8 | uint32_t(buf[2]) << 16 |
                        uint32_t(buf[3]) << 24);
    }
    std::fclose(f);
    return words;
}

int main(int argc, char** argv) {
    if (argc != 4) {
        std::fprintf(stderr, "usage: %s inputs.bin outputs.bin extra_cycles\n", argv[0]);
        return 2;
    }
    const std::vector<uint32_t> in = read_words(argv[1]);
    if (in.empty() || in.size() % 3 != 0) {
        std::fprintf(stderr, "%s: expected a non-empty list of u32 triples\n", argv[1]);
        return 2;
    }
    const size_t n = in.size() / 3;
    const size_t cycles = n + size_t(std::strtoul(argv[3], nullptr, 10));

    auto context = std::make_unique<VerilatedContext>();
    auto top = std::make_unique<Vtb_top>(context.get());
    std::vector<uint32_t> out(cycles);

    top->clk = 0;
    for (size_t cycle = 0; cycle < cycles; ++cycle) {
        const size_t k = cycle < n ? cycle : n - 1;
        top->a = in[3 * k];
        top->b = in[3 * k + 1];
        top->c = in[3 * k + 2];
        top->eval();
        out[cycle] = top->y;
        top->clk = 1;
        top->eval();
        top->clk = 0;
        top->eval();
    }
    top->final();

    FILE* f = std::fopen(argv[2], "wb");
    if (!f) {
        std::perror(argv[2]);
        return 2;
    }
    for (uint32_t w : out) {
        const uint8_t buf[4] = {uint8_t(w), uint8_t(w >> 8), uint8_t(w >> 16), uint8_t(w >> 24)};
        std::fwrite(buf, 1, 4, f);
    }
    if (std::fclose(f) != 0) {
        std::perror(argv[2]);
        return 2;
    }
    return 0;
}
