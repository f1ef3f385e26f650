// Verilator testbench of the serial scene loader alone (rtl::system::run): sends a
// byte stream into its UART pin as a bit-level 8N1 waveform and logs what it writes.
//
// Usage: Vsim STREAM.bin TX_CLOCKS_PER_BIT RESULTS.txt
//
// The bytes go back to back from cycle 64, TX_CLOCKS_PER_BIT cycles a bit (a real
// number: the sender's clock may be off the receiver's), and the run goes on for 40
// bit times after the last stop bit. Results: a `write ADDR FIELD HEX` line per memory
// write in order, `errors N` (rises of the error output), `error 0|1` and `loaded C`
// (the cycle it rose, -1: never) at the end, and the frame registers: `width`,
// `height`, `per_unit`, `prim_count`, `background` (decimal) and `vector K HEX` for
// the 21 vector words.
#include "Vuart_scene_loader.h"
#include "verilated.h"

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <vector>

int main(int argc, char** argv) {
    if (argc != 4) {
        std::fprintf(stderr, "usage: %s STREAM.bin TX_CLOCKS_PER_BIT RESULTS.txt\n", argv[0]);
        return 2;
    }
    std::FILE* in = std::fopen(argv[1], "rb");
    if (!in) {
        std::perror(argv[1]);
        return 2;
    }
    std::vector<uint8_t> bits;
    for (int c; (c = std::fgetc(in)) != EOF;) {
        bits.push_back(0);
        for (int b = 0; b < 8; b++) bits.push_back((c >> b) & 1);
        bits.push_back(1);
    }
    std::fclose(in);
    const double cpb = std::strtod(argv[2], nullptr);
    if (cpb < 1.0) {
        std::fprintf(stderr, "TX_CLOCKS_PER_BIT >= 1 is required\n");
        return 2;
    }
    std::FILE* out = std::fopen(argv[3], "w");
    if (!out) {
        std::perror(argv[3]);
        return 2;
    }
    const uint64_t tx_start = 64;
    const uint64_t cycles = tx_start + uint64_t(cpb * double(bits.size() + 40));

    Verilated::commandArgs(1, argv);
    Vuart_scene_loader* top = new Vuart_scene_loader;
    top->clk = 0;
    top->rx = 1;
    top->eval();
    long long loaded = -1;
    unsigned errors = 0;
    bool error_before = false;
    for (uint64_t cycle = 0; cycle < cycles; cycle++) {
        uint8_t level = 1;
        if (cycle >= tx_start) {
            uint64_t k = uint64_t(double(cycle - tx_start) / cpb);
            if (k < bits.size()) level = bits[k];
        }
        top->rx = level;
        top->clk = 1;
        top->eval();
        if (top->load_we)
            std::fprintf(out, "write %u %u %08X\n", (unsigned)top->load_addr,
                         (unsigned)top->load_field, (unsigned)top->load_data);
        if (top->error && !error_before) errors++;
        error_before = top->error;
        if (loaded < 0 && top->loaded) loaded = (long long)cycle;
        top->clk = 0;
        top->eval();
    }
    std::fprintf(out, "errors %u\nerror %d\nloaded %lld\n", errors, top->error ? 1 : 0, loaded);
    std::fprintf(out, "width %u\nheight %u\nper_unit %u\nprim_count %u\nbackground %u\n",
                 (unsigned)top->width, (unsigned)top->height, (unsigned)top->per_unit,
                 (unsigned)top->prim_count, (unsigned)top->background);
    for (int k = 0; k < 21; k++) std::fprintf(out, "vector %d %08X\n", k, (unsigned)top->vectors[k]);
    std::fclose(out);
    top->final();
    delete top;
    return 0;
}
