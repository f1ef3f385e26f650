// Verilator testbench of the generated pipeline (rtprof hw sim): loads the scene
// memory and the frame constants from a text file, runs one frame, writes the frame
// buffer as a PGM image and the measurements as `key value` lines.
//
// Usage: Vraycaster_top INPUT IMAGE.pgm RESULTS.txt
// INPUT lines: `width W`, `height H`, `per_unit c`, `prim_count n`, `max_cycles N`,
// `background G`, vectors `scan_line|row_step|column_step|eye|view_dir|light|light_dir
// X Y Z` (IEEE-754 bits in hex), and `word PRIMITIVE FIELD HEX` per memory word.
//
// Cycle 0 is the first pixel's issue. Results: `cycles` (the last frame-buffer write),
// `writes`, and per monitored block `latency NAME L` (its first valid output minus its
// first valid input; -1 when it never produced one).
#include "Vraycaster_top.h"
#include "verilated.h"

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

struct Word {
    uint32_t prim, field, value;
};

static void tick(Vraycaster_top* top) {
    top->clk = 1;
    top->eval();
}

static void tock(Vraycaster_top* top) {
    top->clk = 0;
    top->eval();
}

int main(int argc, char** argv) {
    if (argc < 4) {
        std::fprintf(stderr, "usage: %s INPUT IMAGE.pgm RESULTS.txt\n", argv[0]);
        return 2;
    }
    Verilated::commandArgs(1, argv);
    Vraycaster_top* top = new Vraycaster_top;
    std::ifstream in(argv[1]);
    if (!in) {
        std::fprintf(stderr, "cannot read %s\n", argv[1]);
        return 2;
    }
    uint32_t width = 0, height = 0;
    uint64_t max_cycles = 0;
    std::vector<Word> words;
    std::string line;
    while (std::getline(in, line)) {
        std::istringstream s(line);
        std::string key;
        s >> key;
        auto vec = [&](uint32_t& x, uint32_t& y, uint32_t& z) { s >> std::hex >> x >> y >> z; };
        uint32_t x = 0, y = 0, z = 0;
        if (key == "width") { s >> width; top->width = width; }
        else if (key == "height") { s >> height; top->height = height; }
        else if (key == "per_unit") { uint32_t v; s >> v; top->per_unit = v; }
        else if (key == "prim_count") { uint32_t v; s >> v; top->prim_count = v; }
        else if (key == "max_cycles") { s >> max_cycles; }
        else if (key == "background") { uint32_t v; s >> v; top->background = v; }
        else if (key == "scan_line") { vec(x, y, z); top->scan_line_x = x; top->scan_line_y = y; top->scan_line_z = z; }
        else if (key == "row_step") { vec(x, y, z); top->row_step_x = x; top->row_step_y = y; top->row_step_z = z; }
        else if (key == "column_step") { vec(x, y, z); top->column_step_x = x; top->column_step_y = y; top->column_step_z = z; }
        else if (key == "eye") { vec(x, y, z); top->eye_x = x; top->eye_y = y; top->eye_z = z; }
        else if (key == "view_dir") { vec(x, y, z); top->view_dir_x = x; top->view_dir_y = y; top->view_dir_z = z; }
        else if (key == "light") { vec(x, y, z); top->light_x = x; top->light_y = y; top->light_z = z; }
        else if (key == "light_dir") { vec(x, y, z); top->light_dir_x = x; top->light_dir_y = y; top->light_dir_z = z; }
        else if (key == "word") {
            Word w;
            s >> std::dec >> w.prim >> w.field >> std::hex >> w.value;
            words.push_back(w);
        }
    }
    if (width == 0 || height == 0 || max_cycles == 0) {
        std::fprintf(stderr, "%s: width, height and max_cycles are required\n", argv[1]);
        return 2;
    }
    top->start = 0;
    top->load_we = 0;
    tock(top);
    // The loader: one word per cycle.
    for (const Word& w : words) {
        top->load_we = 1;
        top->load_addr = w.prim;
        top->load_field = w.field;
        top->load_data = w.value;
        tick(top);
        tock(top);
    }
    top->load_we = 0;
    top->start = 1;

    std::vector<uint8_t> image(static_cast<size_t>(width) * height, 0);
    const int BLOCKS = 5;
    const char* names[BLOCKS] = {"primary_ray", "intersection", "min_distance", "min_tree", "shading"};
    int64_t first_in[BLOCKS], first_out[BLOCKS];
    for (int b = 0; b < BLOCKS; b++) first_in[b] = first_out[b] = -1;
    int64_t cycle = -1;  // -1 until the first issue
    int64_t last_write = -1;
    uint64_t writes = 0, steps = 0;
    bool timed_out = false;
    while (!top->done) {
        tick(top);
        if (cycle < 0 && top->issuing) cycle = 0;
        if (cycle >= 0) {
            for (int b = 0; b < BLOCKS; b++) {
                if (first_in[b] < 0 && ((top->mon_in >> b) & 1)) first_in[b] = cycle;
                if (first_in[b] >= 0 && first_out[b] < 0 && ((top->mon_out >> b) & 1)) first_out[b] = cycle;
            }
            if (top->fb_we) {
                if (top->fb_addr < image.size()) image[top->fb_addr] = top->fb_data;
                writes++;
                last_write = cycle;
            }
        }
        tock(top);
        if (cycle >= 0) cycle++;
        if (++steps > max_cycles) {
            timed_out = true;
            break;
        }
    }
    std::FILE* pgm = std::fopen(argv[2], "wb");
    if (!pgm) {
        std::fprintf(stderr, "cannot write %s\n", argv[2]);
        return 2;
    }
    std::fprintf(pgm, "P5\n%u %u\n255\n", width, height);
    std::fwrite(image.data(), 1, image.size(), pgm);
    std::fclose(pgm);
    std::FILE* out = std::fopen(argv[3], "w");
    if (!out) {
        std::fprintf(stderr, "cannot write %s\n", argv[3]);
        return 2;
    }
    std::fprintf(out, "cycles %lld\nwrites %llu\ntimed_out %d\n", (long long)last_write,
                 (unsigned long long)writes, timed_out ? 1 : 0);
    for (int b = 0; b < BLOCKS; b++) {
        long long l = (first_in[b] >= 0 && first_out[b] >= 0) ? first_out[b] - first_in[b] : -1;
        std::fprintf(out, "latency %s %lld\n", names[b], l);
    }
    std::fclose(out);
    top->final();
    delete top;
    return timed_out ? 3 : 0;
}
