//! `rtprof hw table` as text: the model's tables 7 and 8 beside the thesis's, in the
//! report's table layout (one table model, printed in columns), and the Yosys columns
//! when a synthesis of the design's RTL was kept.

use hwmodel::blocks::Pipeline;
use hwmodel::design::Design;
use hwmodel::library::{DeviceSpec, Library};
use hwmodel::table::{Row, Tables};
use reports::sections::hardware::hw_table;
use results::HwRow;

/// `rtprof hw table`: tables 7 and 8 of `design` on `device`, the Yosys columns when a
/// synthesis was kept, and with `detail` each block's operators and delay lines.
pub fn table_text(lib: &Library, device: &DeviceSpec, design: &Design, detail: bool) -> String {
    let tables = hwmodel::table::tables(lib, design);
    let mut text = tables_text(&tables, lib, device);
    text += "\n";
    text += &synthesis_text(lib, design);
    if detail {
        text += &Pipeline::build(lib, design).detail_text();
    }
    text
}

/// Tables 7 and 8 with a heading that names the operator library, device and design.
pub fn tables_text(tables: &Tables, lib: &Library, device: &DeviceSpec) -> String {
    let unvalidated = |validated: bool| if validated { "" } else { " (unvalidated)" };
    let mut out = format!(
        "Operator library: {}{}; device {}{}; design: {}\n\
         cells: model / thesis (error); the thesis's figures are the reference, never inputs\n\n",
        lib.family,
        unvalidated(lib.validated),
        device.name,
        unvalidated(device.validated),
        tables.design,
    );
    out += "Table 7: operations (IP cores from the library; composites built from them)\n";
    out += &rows_text(&tables.ops);
    out += "\nTable 8: blocks (dataflow graphs, ASAP schedule, delay-balancing)\n";
    out += &rows_text(&tables.blocks);
    out += "\nThe standalone dot-product row of table 7 is a four-lane module (4 multipliers,\n\
            3 adders: 28 elements); the blocks use three lanes. See docs/hardware-model.md.\n";
    out
}

/// Yosys's columns beside table 8 for `design`, when `rtprof hw synth` kept a synthesis
/// of its RTL on this machine (the RTL is generated for the Cyclone IV E library only).
pub fn synthesis_text(lib: &Library, design: &Design) -> String {
    let rtl_lib = Library::cyclone_iv_e();
    if lib.family != rtl_lib.family {
        return format!(
            "Yosys's columns: the RTL is generated for {} only.\n",
            rtl_lib.family
        );
    }
    let pipeline = Pipeline::build(&rtl_lib, design);
    match rtl::synth::recall(&rtl::synth::cache_dir(), &rtl_lib, &pipeline) {
        Some(synthesis) => {
            let rows: Vec<HwRow> = hwmodel::table::tables(&rtl_lib, design)
                .blocks
                .iter()
                .map(HwRow::from_model_row)
                .collect();
            format!(
                "The generated RTL through Yosys (kept by `rtprof hw synth`):\n{}",
                reports::sections::synthesis::synthesis_text(&synthesis, &rows)
            )
        }
        None => format!(
            "Yosys's columns (LUT4, FF, logic depth, estimated Fmax): no synthesis of the {} design's RTL kept on this machine; `rtprof hw synth` with the same design flags runs one (minutes) and keeps it.\n",
            design.label()
        ),
    }
}

fn rows_text(rows: &[Row]) -> String {
    let rows: Vec<HwRow> = rows.iter().map(HwRow::from_model_row).collect();
    reports::text::table(&hw_table(&rows))
}
