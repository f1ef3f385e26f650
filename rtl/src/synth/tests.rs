//! The synthesis report's parsing and roll-up, on `stat` outputs of real Yosys runs.

use super::*;

// `stat` of a real run (Yosys 0.23, the flow of `script`) of this design, with
// the library's fp_delay.v and fp_mul.v:
//
//     module ram_blk(input clk, input we, input [7:0] wa, input [7:0] ra, input [31:0] d, output reg [31:0] q);
//       reg [31:0] m [0:255];
//       always @(posedge clk) begin if (we) m[wa] <= d; q <= m[ra]; end
//     endmodule
//     module sample_top(input clk, input [31:0] a, input [31:0] b, input we, input [7:0] wa, input [7:0] ra,
//                       output [31:0] y0, output [31:0] y1, output [31:0] y2, output [31:0] q);
//       fp_mul #(.LATENCY(2)) m0 (.clk(clk), .a(a), .b(b), .y(y0));
//       fp_mul #(.LATENCY(2)) m1 (.clk(clk), .a(b), .b(a), .y(y1));
//       fp_mul #(.LATENCY(1)) m2 (.clk(clk), .a(a), .b(a), .y(y2));
//       ram_blk r0 (.clk(clk), .we(we), .wa(wa), .ra(ra), .d(a), .q(q));
//     endmodule

const STAT_SAMPLE: &str = r#"
10. Printing statistics.

=== $paramod$034035bcd992107f1710cd84d8e56530c58b5531\fp_delay ===

   Number of wires:                  4
   Number of wire bits:            129
   Number of public wires:           4
   Number of public wire bits:     129
   Number of memories:               0
   Number of memory bits:            0
   Number of processes:              0
   Number of cells:                 64
     dffeas                         64

=== $paramod$0d3382739923d207fae774c3f37fc69270b7e514\fp_delay ===

   Number of wires:                  3
   Number of wire bits:             65
   Number of public wires:           3
   Number of public wire bits:      65
   Number of memories:               0
   Number of memory bits:            0
   Number of processes:              0
   Number of cells:                 32
     dffeas                         32

=== $paramod\fp_mul\LATENCY=s32'00000000000000000000000000000001 ===

   Number of wires:                 83
   Number of wire bits:            421
   Number of public wires:           6
   Number of public wire bits:     177
   Number of memories:               0
   Number of memory bits:            0
   Number of processes:              0
   Number of cells:                188
     $paramod$0d3382739923d207fae774c3f37fc69270b7e514\fp_delay      1
     cycloneive_lcell_comb         186
     fp_mul_array                    1

=== $paramod\fp_mul\LATENCY=s32'00000000000000000000000000000010 ===

   Number of wires:                 91
   Number of wire bits:            475
   Number of public wires:           6
   Number of public wire bits:     177
   Number of memories:               0
   Number of memory bits:            0
   Number of processes:              0
   Number of cells:                202
     $paramod$034035bcd992107f1710cd84d8e56530c58b5531\fp_delay      1
     cycloneive_lcell_comb         200
     fp_mul_array                    1

=== fp_mul_array ===

   Number of wires:                695
   Number of wire bits:           2327
   Number of public wires:           3
   Number of public wire bits:      96
   Number of memories:               0
   Number of memory bits:            0
   Number of processes:              0
   Number of cells:               1616
     cycloneive_lcell_comb        1616

=== ram_blk ===

   Number of wires:                  7
   Number of wire bits:             86
   Number of public wires:           6
   Number of public wire bits:      82
   Number of memories:               0
   Number of memory bits:            0
   Number of processes:              0
   Number of cells:                  1
     altsyncram                      1

=== sample_top ===

   Number of wires:                 10
   Number of wire bits:            210
   Number of public wires:          10
   Number of public wire bits:     210
   Number of memories:               0
   Number of memory bits:            0
   Number of processes:              0
   Number of cells:                  4
     $paramod\fp_mul\LATENCY=s32'00000000000000000000000000000001      1
     $paramod\fp_mul\LATENCY=s32'00000000000000000000000000000010      2
     ram_blk                         1

=== design hierarchy ===

   sample_top                        1
     $paramod\fp_mul\LATENCY=s32'00000000000000000000000000000001      1
       $paramod$0d3382739923d207fae774c3f37fc69270b7e514\fp_delay      1
       fp_mul_array                  1
     $paramod\fp_mul\LATENCY=s32'00000000000000000000000000000010      2
       $paramod$034035bcd992107f1710cd84d8e56530c58b5531\fp_delay      1
       fp_mul_array                  1
     ram_blk                         1

   Number of wires:               2378
   Number of wire bits:           8971
   Number of public wires:          54
   Number of public wire bits:    1434
   Number of memories:               0
   Number of memory bits:            0
   Number of processes:              0
   Number of cells:               5595
     altsyncram                      1
     cycloneive_lcell_comb        5434
     dffeas                        160

"#;

// The same run's `stat` before mapping (stat_rtl.txt), two of its sections.
const STAT_RTL_SAMPLE: &str = r#"=== ram_blk ===

   Number of wires:                 17
   Number of wire bits:            362
   Number of public wires:           6
   Number of public wire bits:      82
   Number of memories:               1
   Number of memory bits:         8192
   Number of processes:              1
   Number of cells:                  1
     $memrd                          1


=== $paramod\fp_mul\LATENCY=s32'00000000000000000000000000000001 ===

   Number of wires:                 85
   Number of wire bits:            971
   Number of public wires:          23
   Number of public wire bits:     330
   Number of memories:               0
   Number of memory bits:            0
   Number of processes:              1
   Number of cells:                 35
     $add                            4
     $and                            1
     $eq                             8
     $ge                             1
     $le                             1
     $logic_and                      6
     $logic_or                       5
     $ne                             2
     $or                             1
     $paramod$0d3382739923d207fae774c3f37fc69270b7e514\fp_delay      1
     $reduce_or                      2
     $sub                            1
     $xor                            1
     fp_mul_array                    1

"#;

fn sample_report(blocks: &[&str]) -> SynthReport {
    let stat = parse_stat(STAT_SAMPLE).unwrap();
    let stat_rtl = parse_stat(STAT_RTL_SAMPLE).unwrap();
    report_from_stats("sample_top", &stat, &stat_rtl, blocks, &[]).unwrap()
}

const MUL_L1: &str = "$paramod\\fp_mul\\LATENCY=s32'00000000000000000000000000000001";
const MUL_L2: &str = "$paramod\\fp_mul\\LATENCY=s32'00000000000000000000000000000010";

#[test]
fn stat_is_parsed_per_module() {
    let stat = parse_stat(STAT_SAMPLE).unwrap();
    // Seven modules; the `design hierarchy` section is not one.
    assert_eq!(stat.len(), 7);
    assert_eq!(
        stat[MUL_L2].cells,
        BTreeMap::from([
            (
                "$paramod$034035bcd992107f1710cd84d8e56530c58b5531\\fp_delay".to_string(),
                1
            ),
            (LUT4_CELL.to_string(), 200),
            ("fp_mul_array".to_string(), 1),
        ])
    );
    assert_eq!(stat["ram_blk"].cells[M9K_CELL], 1);
    // Memories are mapped: the bits are counted before mapping.
    assert_eq!(stat["ram_blk"].memory_bits, 0);
    assert_eq!(
        parse_stat(STAT_RTL_SAMPLE).unwrap()["ram_blk"].memory_bits,
        8192
    );
}

#[test]
fn the_hierarchy_is_rolled_up() {
    let report = sample_report(&["fp_mul", "ram_blk", "fp_mul_array"]);
    // By hand from the sample: fp_mul_array has 1616 LUTs, all multiplier logic;
    // fp_mul at LATENCY 1 has 186 of its own and a 32-bit, 1-deep delay line; at
    // LATENCY 2, 200 and a 2-deep delay line (64 flip-flops).
    let mul_l1 = SynthFigures {
        lut4: 186 + 1616,
        ff: 32,
        mult_lut4: 1616,
        ..SynthFigures::default()
    };
    let mul_l2 = SynthFigures {
        lut4: 200 + 1616,
        ff: 64,
        mult_lut4: 1616,
        ..SynthFigures::default()
    };
    let ram = SynthFigures {
        mem_bits: 256 * 32,
        m9k: 1,
        ..SynthFigures::default()
    };
    let array = SynthFigures {
        lut4: 1616,
        mult_lut4: 1616,
        ..SynthFigures::default()
    };
    let block = |module: &str, instances, figures| BlockFigures {
        block: base_name(module).to_string(),
        module: module.to_string(),
        instances,
        figures,
    };
    assert_eq!(
        report.blocks,
        [
            block(MUL_L1, 1, mul_l1),
            block(MUL_L2, 2, mul_l2),
            block("ram_blk", 1, ram),
            block("fp_mul_array", 3, array),
        ]
    );
    assert_eq!(report.block("fp_mul").map(|b| b.instances), Some(1));
    // The top: one fp_mul at LATENCY 1, two at LATENCY 2 and the RAM. Yosys's own
    // `design hierarchy` totals agree: 5434 LUTs, 160 flip-flops, 1 M9K.
    assert_eq!(
        report.total,
        SynthFigures {
            lut4: 1802 + 2 * 1816,
            ff: 32 + 2 * 64,
            mem_bits: 8192,
            m9k: 1,
            mult_lut4: 3 * 1616,
        }
    );
    assert_eq!(report.total.lut4, 5434);
    assert_eq!(report.total.ff, 160);
    assert_eq!(report.modules.len(), 7);
    assert_eq!(report.modules["sample_top"].instances, 1);
    assert_eq!(
        report.modules["$paramod$034035bcd992107f1710cd84d8e56530c58b5531\\fp_delay"].instances,
        2
    );
    assert!(report.unmapped.is_empty());
}

#[test]
fn missing_blocks_and_unmapped_cells_are_reported() {
    let stat = parse_stat(STAT_SAMPLE).unwrap();
    let err =
        report_from_stats("sample_top", &stat, &BTreeMap::new(), &["fp_div"], &[]).unwrap_err();
    assert!(err.to_string().contains("`fp_div`"), "{err}");
    assert!(report_from_stats("nope", &stat, &BTreeMap::new(), &[], &[]).is_err());

    // The coarse `$mux` synth_intel can leave behind (see the module doc).
    let text = STAT_SAMPLE.replace(
        "     cycloneive_lcell_comb         186\n",
        "     $mux                            1\n     cycloneive_lcell_comb         186\n",
    );
    let stat = parse_stat(&text).unwrap();
    let report = report_from_stats("sample_top", &stat, &BTreeMap::new(), &[], &[]).unwrap();
    assert_eq!(
        report.unmapped,
        [UnmappedCells {
            module: MUL_L1.to_string(),
            cell: "$mux".to_string(),
            count: 1,
        }]
    );
    assert_eq!(report.total.lut4, 5434);
    assert_eq!(report.total.mem_bits, 0);

    // A black box's instances are neither figures nor unmapped cells: `fp_mul_array`
    // read by its ports only leaves its module out of the statistics.
    let stat: BTreeMap<String, ModuleStat> = parse_stat(STAT_SAMPLE)
        .unwrap()
        .into_iter()
        .filter(|(m, _)| m != "fp_mul_array")
        .collect();
    let unboxed = report_from_stats("sample_top", &stat, &BTreeMap::new(), &[], &[]).unwrap();
    assert!(unboxed.unmapped.iter().any(|u| u.cell == "fp_mul_array"));
    let boxed = report_from_stats(
        "sample_top",
        &stat,
        &BTreeMap::new(),
        &[],
        &["fp_mul_array"],
    )
    .unwrap();
    assert!(boxed.unmapped.is_empty(), "{:?}", boxed.unmapped);
    assert_eq!(boxed.total.mult_lut4, 0);
    assert_eq!(unboxed.total, boxed.total);
}

#[test]
fn malformed_stat_is_an_error() {
    assert!(parse_stat("").is_err());
    assert!(parse_stat("=== m ===\n   Number of cells:   x\n").is_err());
    assert!(parse_stat("=== m ===\n   dffeas 3\n").is_err());
}

#[test]
fn parameter_decorations_are_stripped() {
    assert_eq!(base_name(MUL_L1), "fp_mul");
    assert_eq!(
        base_name("$paramod$034035bcd992107f1710cd84d8e56530c58b5531\\fp_delay"),
        "fp_delay"
    );
    assert_eq!(base_name("fp_mul_array"), "fp_mul_array");
    assert_eq!(base_name("\\top"), "top");
}

#[test]
fn the_script_keeps_the_hierarchy() {
    let text = script(
        &[PathBuf::from("/a b/fp_mul.v")],
        &[],
        "synth_top",
        &["blk"],
    )
    .unwrap();
    assert!(text.contains("read_verilog \"/a b/fp_mul.v\"\n"), "{text}");
    assert!(
        text.contains("synth_intel -family cycloneive -top synth_top -noflatten -run map_cells:\n"),
        "{text}"
    );
    // Yosys's default LUT mapping (issue 38: no `abc -fast`).
    assert!(
        text.contains("\nabc -lut 4\n") && !text.contains("-fast -lut"),
        "{text}"
    );
    assert!(text.contains("tee -o stat.txt stat\n"), "{text}");
    // The whole design's depth, then the block's from the saved netlist.
    assert!(
        text.contains("tee -o ltp-synth_top.txt ltp -noff"),
        "{text}"
    );
    assert!(
        text.contains("design -load mapped\nhierarchy -top blk\nflatten\ntee -o ltp-blk.txt"),
        "{text}"
    );
    assert!(script(&[PathBuf::from("/a\"b.v")], &[], "t", &[]).is_err());
    assert!(!is_identifier("a b") && !is_identifier("1a") && is_identifier("fp_mul"));
}

#[test]
fn black_boxes_are_read_by_their_ports_and_end_paths() {
    let boxed = BlackBox {
        module: "blk".into(),
        file: PathBuf::from("/src/blk.v"),
    };
    let text = script(&[PathBuf::from("/src/top.v")], &[boxed], "top", &[]).unwrap();
    assert!(text.contains("read_verilog \"/src/top.v\"\n"), "{text}");
    assert!(
        text.contains("read_verilog -lib \"/src/blk.v\"\n"),
        "{text}"
    );
    // Registers, memory blocks and the black box are left out of the path's cells.
    assert!(
        text.contains("ltp -noff t:dffeas t:altsyncram %u t:blk %u %n\n"),
        "{text}"
    );
    let plain = script(&[PathBuf::from("/src/top.v")], &[], "top", &[]).unwrap();
    assert!(
        plain.contains(&format!("ltp -noff {LTP_SELECTION}\n")),
        "{plain}"
    );
}

#[test]
fn a_missing_yosys_says_how_to_install_it() {
    let err = yosys_version("rtprof-no-such-yosys").unwrap_err();
    assert!(
        matches!(err, RtlError::ToolMissing { tool: "yosys", .. }),
        "{err}"
    );
    assert!(
        err.to_string().contains("scripts/install-rtl-tools.sh"),
        "{err}"
    );
    assert!(err.to_string().contains("apt-get install yosys"), "{err}");
}

/// A top that instantiates `op` at `latency` (the parameters cannot be set from
/// `synth_intel -top`).
fn wrapper(op: crate::Operator, latency: u32) -> String {
    let ports = op.ports();
    let (output, inputs) = ports.split_last().unwrap();
    let width = |port: &str| match port {
        "clk" | "sub" | "sel" | "lt" => "",
        _ => " [31:0]",
    };
    let mut decls: Vec<String> = inputs
        .iter()
        .map(|p| format!("input{} {p}", width(p)))
        .collect();
    decls.push(format!("output{} {output}", width(output)));
    let conns: Vec<String> = ports.iter().map(|p| format!(".{p}({p})")).collect();
    format!(
        "module synth_top ({});\n    {} #(.LATENCY({latency})) u ({});\nendmodule\n",
        decls.join(", "),
        op.module_name(),
        conns.join(", ")
    )
}

fn synthesize_operator(op: crate::Operator, latency: u32) -> BlockFigures {
    let dir = std::env::temp_dir().join(format!(
        "rtl-synth-{}-{}",
        op.module_name(),
        std::process::id()
    ));
    let mut files = crate::write_sources(&dir.join("src")).unwrap();
    let top = dir.join("src").join("synth_top.v");
    fs::write(&top, wrapper(op, latency)).unwrap();
    files.push(top);
    let report = synthesize(
        &dir.join("yosys"),
        &files,
        "synth_top",
        &[op.module_name()],
        &[],
    )
    .unwrap_or_else(|e| panic!("{e}"));
    eprintln!(
        "{} at LATENCY {latency}: {:?} in {:.1} s ({})",
        op.module_name(),
        report.total,
        report.seconds,
        report.yosys
    );
    assert!(report.unmapped.is_empty(), "{:?}", report.unmapped);
    assert_eq!(report.check_problems, 0, "{}", report.log.display());
    assert!(
        report.warnings.iter().all(|w| w.contains("experimental")),
        "{:?}",
        report.warnings
    );
    assert_eq!(report.blocks.len(), 1);
    let block = report.blocks[0].clone();
    assert_eq!(block.instances, 1);
    // The wrapper adds nothing.
    assert_eq!(block.figures, report.total);
    fs::remove_dir_all(&dir).unwrap();
    block
}

#[test]
#[ignore = "needs yosys"]
fn synth_errors_carry_yosys_messages() {
    let dir = std::env::temp_dir().join(format!("rtl-synth-error-{}", std::process::id()));
    fs::create_dir_all(&dir).unwrap();
    let file = dir.join("broken.v");
    fs::write(
        &file,
        "module broken (input a, output y);\n    assign y = ;\nendmodule\n",
    )
    .unwrap();
    let err = synthesize(&dir, &[file], "broken", &[], &[]).unwrap_err();
    let text = err.to_string();
    assert!(
        matches!(err, RtlError::Tool { tool: "yosys", .. }),
        "{text}"
    );
    assert!(
        text.contains("ERROR") && text.contains("synth.log"),
        "{text}"
    );
    fs::remove_dir_all(&dir).unwrap();
}

#[test]
#[ignore = "needs yosys"]
fn synth_fp_add_sub() {
    let f = synthesize_operator(crate::Operator::AddSub, 7).figures;
    // The delay line alone holds LATENCY × 32 result bits.
    assert!(f.ff >= 7 * 32, "{f:?}");
    assert!(f.lut4 > 0, "{f:?}");
    assert_eq!(f.mult_lut4, 0);
    assert_eq!((f.mem_bits, f.m9k), (0, 0));
}

#[test]
#[ignore = "needs yosys"]
fn synth_fp_mul() {
    let f = synthesize_operator(crate::Operator::Multiply, 5).figures;
    assert!(f.ff >= 5 * 32, "{f:?}");
    assert!(f.lut4 > 0, "{f:?}");
    // The 24 x 24 array is most of a multiplier built of LUTs.
    assert!(f.mult_lut4 > 0 && 2 * f.mult_lut4 >= f.lut4, "{f:?}");
    assert!(f.mult_lut4 <= f.lut4, "{f:?}");
    assert_eq!((f.mem_bits, f.m9k), (0, 0));
}
