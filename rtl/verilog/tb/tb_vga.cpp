// Verilator testbench of the VGA controller alone (rtl::system::run): serves its
// frame-memory reads from a file, as a synchronous RAM (the word one clock after its
// address), and records the pins once per pixel clock.
//
// Usage: Vsim FRAME.bin PIXELS TRACE.bin
//
// FRAME.bin: the frame memory, one byte per visible pixel, row by row. Trace: PIXELS
// samples of 4 bytes (flags: bit 0 hsync, 1 vsync, 2 video_on; then R, G, B), from
// the first clock after power-up.
#include "Vvga_controller.h"
#include "verilated.h"

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <vector>

int main(int argc, char** argv) {
    if (argc != 4) {
        std::fprintf(stderr, "usage: %s FRAME.bin PIXELS TRACE.bin\n", argv[0]);
        return 2;
    }
    std::FILE* in = std::fopen(argv[1], "rb");
    if (!in) {
        std::perror(argv[1]);
        return 2;
    }
    std::vector<uint8_t> memory;
    for (int c; (c = std::fgetc(in)) != EOF;) memory.push_back(uint8_t(c));
    std::fclose(in);
    const uint64_t pixels = std::strtoull(argv[2], nullptr, 10);
    std::vector<uint8_t> trace;
    trace.reserve(pixels * 4);

    Verilated::commandArgs(1, argv);
    Vvga_controller* top = new Vvga_controller;
    top->clk = 0;
    top->fb_data = 0;
    top->eval();
    for (uint64_t p = 0; p < pixels; p++) {
        uint64_t address = top->fb_addr;
        top->clk = 1;
        top->eval();
        // The RAM's registered output: the word at the address of the clock before.
        top->fb_data = address < memory.size() ? memory[address] : 0;
        top->eval();
        trace.push_back(uint8_t(top->hsync | top->vsync << 1 | top->video_on << 2));
        trace.push_back(top->red);
        trace.push_back(top->green);
        trace.push_back(top->blue);
        top->clk = 0;
        top->eval();
    }
    std::FILE* t = std::fopen(argv[3], "wb");
    if (!t) {
        std::perror(argv[3]);
        return 2;
    }
    std::fwrite(trace.data(), 1, trace.size(), t);
    std::fclose(t);
    top->final();
    delete top;
    return 0;
}
