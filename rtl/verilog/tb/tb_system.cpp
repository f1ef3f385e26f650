// Verilator testbench of the whole system (rtl::system::run): sends a scene upload
// into the UART pin as a bit-level 8N1 waveform, runs the pipeline until its frame is
// done, then records the VGA pins once per pixel clock.
//
// Usage: Vsim STREAM.bin TX_CLOCKS_PER_BIT PIXEL_DIVIDE MAX_CYCLES TRACE_PIXELS TRACE.bin RESULTS.txt
//
// The transmitter sends the bytes back to back (start bit, 8 data bits least
// significant first, stop bit) from cycle 64, TX_CLOCKS_PER_BIT system cycles a bit
// (a real number: a sender's clock need not match the receiver's). The pixel clock
// rises every PIXEL_DIVIDE (even) system cycles, at a falling edge of the system
// clock. Trace: TRACE_PIXELS samples of 4 bytes (flags: bit 0 hsync, 1 vsync,
// 2 blank_n; then R, G, B), one per pixel clock from the first after `done`. Results:
// `loaded C`, `done C` (system cycles; -1: never), `load_error 0|1`, `tx_end C`,
// `samples N`. Exit code 3: MAX_CYCLES passed first.
#include "Vraycaster_system.h"
#include "verilated.h"

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <vector>

int main(int argc, char** argv) {
    if (argc != 8) {
        std::fprintf(stderr,
                     "usage: %s STREAM.bin TX_CLOCKS_PER_BIT PIXEL_DIVIDE MAX_CYCLES TRACE_PIXELS "
                     "TRACE.bin RESULTS.txt\n",
                     argv[0]);
        return 2;
    }
    std::FILE* in = std::fopen(argv[1], "rb");
    if (!in) {
        std::perror(argv[1]);
        return 2;
    }
    std::vector<uint8_t> bits;  // the line, one level per bit
    for (int c; (c = std::fgetc(in)) != EOF;) {
        bits.push_back(0);
        for (int b = 0; b < 8; b++) bits.push_back((c >> b) & 1);
        bits.push_back(1);
    }
    std::fclose(in);
    const double cpb = std::strtod(argv[2], nullptr);
    const uint64_t divide = std::strtoull(argv[3], nullptr, 10);
    const uint64_t max_cycles = std::strtoull(argv[4], nullptr, 10);
    const uint64_t trace_pixels = std::strtoull(argv[5], nullptr, 10);
    if (cpb < 1.0 || divide < 2 || divide % 2 != 0) {
        std::fprintf(stderr, "TX_CLOCKS_PER_BIT >= 1 and an even PIXEL_DIVIDE >= 2 are required\n");
        return 2;
    }
    const uint64_t tx_start = 64;
    const uint64_t tx_end = tx_start + uint64_t(cpb * double(bits.size())) + 1;

    Verilated::commandArgs(1, argv);
    Vraycaster_system* top = new Vraycaster_system;
    std::vector<uint8_t> trace;
    trace.reserve(trace_pixels * 4);
    top->clk = 0;
    top->pixel_clk = 0;
    top->uart_rx = 1;
    top->eval();
    long long loaded = -1, done = -1;
    bool error_seen = false;
    uint64_t cycle = 0;
    for (; cycle < max_cycles && trace.size() < trace_pixels * 4; cycle++) {
        uint8_t level = 1;
        if (cycle >= tx_start) {
            uint64_t k = uint64_t(double(cycle - tx_start) / cpb);
            if (k < bits.size()) level = bits[k];
        }
        top->uart_rx = level;
        top->clk = 1;
        top->eval();
        if (loaded < 0 && top->loaded) loaded = (long long)cycle;
        if (done < 0 && top->done) done = (long long)cycle;
        if (top->load_error) error_seen = true;
        top->clk = 0;
        uint64_t phase = cycle % divide;
        if (phase == 0) top->pixel_clk = 1;
        if (phase == divide / 2) top->pixel_clk = 0;
        top->eval();
        if (phase == 0 && done >= 0) {
            trace.push_back(uint8_t(top->vga_hsync | top->vga_vsync << 1 | top->vga_blank_n << 2));
            trace.push_back(top->vga_r);
            trace.push_back(top->vga_g);
            trace.push_back(top->vga_b);
        }
    }
    std::FILE* t = std::fopen(argv[6], "wb");
    if (!t) {
        std::perror(argv[6]);
        return 2;
    }
    std::fwrite(trace.data(), 1, trace.size(), t);
    std::fclose(t);
    std::FILE* out = std::fopen(argv[7], "w");
    if (!out) {
        std::perror(argv[7]);
        return 2;
    }
    std::fprintf(out, "loaded %lld\ndone %lld\nload_error %d\ntx_end %llu\nsamples %llu\n", loaded,
                 done, error_seen ? 1 : 0, (unsigned long long)tx_end,
                 (unsigned long long)(trace.size() / 4));
    std::fclose(out);
    top->final();
    delete top;
    return cycle >= max_cycles ? 3 : 0;
}
