//! The top module (the screen iterator, the scene memory, K intersection units with
//! their minimum-distance blocks, the comparator tree, the frame-buffer port) and the
//! hand-written minimum-distance block.

use std::collections::BTreeMap;
use std::fmt::Write as _;

use hwmodel::blocks::{ADDRESS_BITS, Block, Pipeline};
use hwmodel::design::{Design, MinDistance};
use hwmodel::hw_scene::HwPrimitive;
use hwmodel::library::{Library, OpKind};

use super::{BlockModule, FIELDS, Port, TOP};
use crate::RtlError;

/// The hand-written minimum-distance block of `design` at the library's compare and
/// register latencies: the thesis's float compare (fig. 25) or the integer compare.
///
/// `rtl/verilog/min_distance.v` (float) and `min_distance_int.v` (integer) are its
/// text with the latencies as placeholders: `{compare}`, `{register}`, `{total}` (their
/// sum), `{a}` (the address bits) and `{ab}` (`{a}` − 1). Both keep their minimum in
/// one register stage, the integer one compares combinationally and the float one
/// forwards its result to the next primitive's compare, so a library with other
/// latencies would make the block disagree with the model: an error.
pub(super) fn min_distance_module(lib: &Library, design: &Design) -> Result<String, RtlError> {
    let unbuilt = |what: &str, latency: u32, built: u32| {
        RtlError::Generate(format!(
            "min_distance: the library's {what} takes {latency} cycles; the hand-written block is built for {built}"
        ))
    };
    let register = lib.op(OpKind::Register).latency;
    if register != 1 {
        return Err(unbuilt("register", register, 1));
    }
    let (compare, text) = match design.min_distance {
        MinDistance::FloatCompare => {
            // The kept value is forwarded to the next compare when its result appears:
            // primitives must come no faster than the compare decides.
            let compare = lib.op(OpKind::Compare).latency;
            let rate = design.cycles_per_primitive();
            if compare > rate {
                return Err(unbuilt("float compare", compare, rate));
            }
            (compare, include_str!("../../verilog/min_distance.v"))
        }
        MinDistance::IntegerCompare => {
            let compare = lib.op(OpKind::IntCompare).latency;
            if compare != 0 {
                return Err(unbuilt("integer compare", compare, 0));
            }
            (compare, include_str!("../../verilog/min_distance_int.v"))
        }
    };
    let a = ADDRESS_BITS;
    Ok(text
        .replace("{compare}", &compare.to_string())
        .replace("{register}", &register.to_string())
        .replace("{total}", &(compare + register).to_string())
        .replace("{ab}", &(a - 1).to_string())
        .replace("{a}", &a.to_string()))
}

/// Scene-memory words the design reads: (field, bits).
fn fields(design_no_rsqrt: bool) -> Vec<(u32, u32)> {
    let mut f: Vec<(u32, u32)> = (0..HwPrimitive::WORDS as u32)
        .map(|i| (i, if i == 8 { 1 } else { 32 }))
        .collect();
    if design_no_rsqrt {
        f.extend((9..FIELDS).map(|i| (i, 32)));
    }
    f
}

/// The top module's input for a block's frame-constant port `k_<name>`.
fn constant_source(name: &str, block: &str) -> Result<String, RtlError> {
    let (base, axis) = match name.rsplit_once('_') {
        Some((b, a)) if ["x", "y", "z"].contains(&a) => (b, Some(a)),
        _ => (name, None),
    };
    let top = match base {
        "scan_line" | "row_step" | "column_step" | "light" => base.to_string(),
        "O" => "eye".into(),
        "Lhat" => "light_dir".into(),
        "i" => return Ok("row_i".into()),
        "background" => return Ok("background".into()),
        "R" => "view_dir".into(),
        _ => {
            return Err(RtlError::Generate(format!(
                "{block}: no top-level source for frame constant `{name}`"
            )));
        }
    };
    Ok(match axis {
        Some(a) => format!("{top}_{a}"),
        None => top,
    })
}

/// Instantiates a generated block in the top: connects its ports by rule.
fn instance(
    ports: &[Port],
    module: &str,
    name: &str,
    block: &str,
    connect: &dyn Fn(&str) -> Option<String>,
    memory_ports: &mut Vec<(u32, String, String, u32)>,
    decls: &mut String,
) -> Result<String, RtlError> {
    let mut conns = Vec::new();
    for Port {
        output,
        bits,
        name: port,
    } in ports
    {
        let (output, bits) = (*output, *bits);
        let expr = if let Some(e) = connect(port) {
            e
        } else if let Some(k) = port.strip_prefix("k_") {
            constant_source(k, block)?
        } else if let Some(rest) = port.strip_prefix("rd") {
            // rd<id>_addr (output) / rd<id>_f<field> (input)
            let (id, what) = rest.split_once('_').unwrap_or((rest, ""));
            let wire = format!("{name}_rd{id}");
            if what == "addr" {
                format!("{wire}_addr")
            } else {
                let field = what.trim_start_matches('f').parse::<u32>().map_err(|_| {
                    RtlError::Generate(format!("{block}: bad memory port `{port}`"))
                })?;
                writeln!(decls, "    wire [{}:0] {wire}_addr;", ADDRESS_BITS - 1).ok();
                memory_ports.push((field, format!("{wire}_addr"), format!("{wire}_q"), bits));
                format!("{wire}_q")
            }
        } else if output {
            let wire = format!("{name}_{port}");
            writeln!(decls, "    wire [{}:0] {wire};", bits - 1).ok();
            wire
        } else {
            return Err(RtlError::Generate(format!(
                "{block}: nothing drives input port `{port}`"
            )));
        };
        conns.push(format!(".{port}({expr})"));
    }
    Ok(format!(
        "    {module} {name} (\n        {}\n    );\n",
        conns.join(",\n        ")
    ))
}

/// The top's timing: units, memory depth and the row path's cycles.
pub(super) struct TopTiming {
    pub(super) units: u32,
    pub(super) depth_bits: u32,
    /// Cycles from a row's first issue to its base's load into the row registers.
    pub(super) row_load_delay: u32,
    /// Cycles from `start` to the first issue (row 0's base).
    pub(super) prologue: u32,
    /// Cycles the row index runs ahead of the iterator: a row's base is started this
    /// many cycles (less the index's register) before its first issue.
    pub(super) row_lead: u32,
}

/// The screen iterator's counters, their names prefixed with `prefix`: a slot every
/// `rate` cycles (`phase`), primitive `k` of `per_unit` per pixel, pixels in rows, top
/// row first. They run from the cycle after the prologue counter reads `starts_at` to
/// the frame's last slot: two copies started apart stay that many cycles apart.
fn iterator_counters(prefix: &str, rate: u32, starts_at: u32) -> String {
    let bits = (u32::BITS - (rate - 1).leading_zeros()).max(1);
    format!(
        r#"    reg {p}running = 1'b0, {p}finished = 1'b0;
    reg [{b1}:0] {p}phase = {bits}'d0;
    reg [15:0] {p}k = 16'd0, {p}col = 16'd0, {p}row = 16'd0;
    wire {p}slot_end = {p}running & ({p}phase == {bits}'d{last});
    wire {p}last_k = ({p}k == per_unit - 16'd1);
    wire {p}pixel_end = {p}slot_end & {p}last_k;
    always @(posedge clk) begin
        if (start & ~{p}running & ~{p}finished & (prologue == 16'd{starts_at})) {p}running <= 1'b1;
        if ({p}running) {p}phase <= {p}slot_end ? {bits}'d0 : {p}phase + {bits}'d1;
        if ({p}slot_end) begin
            if ({p}last_k) begin
                {p}k <= 16'd0;
                if ({p}col == width - 16'd1) begin
                    {p}col <= 16'd0;
                    if ({p}row == height - 16'd1) begin
                        {p}running <= 1'b0;
                        {p}finished <= 1'b1;
                    end
                    {p}row <= {p}row + 16'd1;
                end else {p}col <= {p}col + 16'd1;
            end else {p}k <= {p}k + 16'd1;
        end
    end
"#,
        p = prefix,
        b1 = bits - 1,
        last = rate - 1,
    )
}

pub(super) fn top_module(
    lib: &Library,
    pipeline: &Pipeline,
    modules: &BTreeMap<&str, BlockModule>,
    t: TopTiming,
) -> Result<String, RtlError> {
    let design = pipeline.design;
    let ab = ADDRESS_BITS;
    let l_ray = pipeline.primary_ray.latency();
    let l_int = pipeline.intersection.latency();
    let l_min = pipeline.min_distance.latency();
    let l_tree = pipeline.min_tree.as_ref().map_or(0, Block::latency);
    let l_shade = pipeline.shading.latency();
    let l_mem = lib.op(OpKind::RamRead).latency;
    if l_ray < l_mem {
        return Err(RtlError::Generate(format!(
            "the primary ray ({l_ray} cycles) is shorter than a memory read ({l_mem})"
        )));
    }
    let block_ports = |name: &str| {
        modules
            .get(name)
            .map(|m| m.ports.as_slice())
            .ok_or_else(|| RtlError::Generate(format!("no generated `{name}` block")))
    };
    let mut decls = String::new();
    let mut body = String::new();
    let mut memory_ports: Vec<(u32, String, String, u32)> = Vec::new();

    let vec3 = |name: &str| {
        ["x", "y", "z"]
            .map(|a| format!("input [31:0] {name}_{a}"))
            .join(", ")
    };
    let ports = [
        "input clk".to_string(),
        "input start".into(),
        "input load_we".into(),
        format!("input [{}:0] load_addr", ab - 1),
        "input [3:0] load_field".into(),
        "input [31:0] load_data".into(),
        "input [15:0] width".into(),
        "input [15:0] height".into(),
        "input [15:0] per_unit".into(),
        "input [15:0] prim_count".into(),
        vec3("scan_line"),
        vec3("row_step"),
        vec3("column_step"),
        vec3("eye"),
        vec3("view_dir"),
        vec3("light"),
        vec3("light_dir"),
        "input [7:0] background".into(),
        "output fb_we".into(),
        "output [31:0] fb_addr".into(),
        "output [7:0] fb_data".into(),
        "output done".into(),
        "output issuing".into(),
        "output [7:0] mon_in".into(),
        "output [7:0] mon_out".into(),
    ];

    // Screen iterator: one slot every `rate` cycles (the minimum distance's hold);
    // primitive k of c per pixel.
    let rate = design.cycles_per_primitive();
    if rate == 0 || t.row_lead > t.prologue {
        return Err(RtlError::Generate(format!(
            "the iterator: {rate} cycles a primitive, the row index {} cycles ahead in a {}-cycle prologue",
            t.row_lead, t.prologue
        )));
    }
    let lead_start = t.prologue - t.row_lead;
    writeln!(
        body,
        r#"    // Screen iterator (thesis 6.1.2): after the prologue (row 0's base), one slot
    // every {rate} cycle(s), as long as the minimum distance holds a primitive;
    // primitive k of per_unit, pixels in rows, top row first.
    reg [15:0] prologue = 16'd0;
    always @(posedge clk)
        if (start & ~running & ~finished & (prologue != 16'd{prologue})) prologue <= prologue + 16'd1;
{counters}    wire slot = running & (phase == 0);
    wire issue = slot & (k == 16'd0);
    assign issuing = running;
    // Pixels issued: the frame is done when as many were written (a count, not
    // width * height: a 16 x 16 product in LUTs is twice the 12 levels a cycle allows).
    reg [31:0] issued = 32'd0;
    always @(posedge clk) if (issue) issued <= issued + 32'd1;
    // A 16-bit count as a float: exact (below 2^24), the leading one and a shift.
    function [31:0] u16_to_float(input [15:0] n);
        integer b;
        reg [4:0] msb;
        reg [38:0] shifted;
        begin
            msb = 5'd0;
            for (b = 0; b < 16; b = b + 1) if (n[b]) msb = b[4:0];
            shifted = {{n, 23'd0}} >> msb;
            u16_to_float = (n == 16'd0) ? 32'd0 : {{1'b0, 8'd127 + {{3'd0, msb}}, shifted[22:0]}};
        end
    endfunction
    // j as a float for the pixel issued now, in a register loaded as the pixel starts,
    // so that no conversion lies between the iterator and the primary ray: converted
    // from col_ahead, the next pixel's column kept beside col (set in the prologue,
    // advanced with it), which is in time even when col changes every cycle.
    reg [15:0] col_ahead = 16'd0;
    always @(posedge clk)
        if (~running & ~finished) col_ahead <= (width == 16'd1) ? 16'd0 : 16'd1;
        else if (pixel_end) col_ahead <= (col_ahead == width - 16'd1) ? 16'd0 : col_ahead + 16'd1;
    reg [31:0] col_f = 32'd0;
    always @(posedge clk) if (pixel_end) col_f <= u16_to_float(col_ahead);
    // i, registered, for the row path: row r's base loads into the row registers
    // {row_load_delay} cycles after r's first issue, from the i the path read
    // {row_read} cycles before. A copy of the counters running {row_lead} cycles ahead
    // has that row one cycle early, however short a row is (one pixel a cycle, one
    // pixel wide): counting rows once per row base instead needs rows of at least the
    // row path.
{lead_counters}    reg [31:0] row_i = 32'd0;
    always @(posedge clk) row_i <= u16_to_float(lead_row);
    wire row_first_issue = issue & (col == 16'd0);
    wire row_load;
    fp_delay #(.WIDTH(1), .LATENCY({row_load_delay})) row_load_line (.clk(clk), .d(row_first_issue), .q(row_load));
"#,
        prologue = t.prologue,
        counters = iterator_counters("", rate, t.prologue),
        lead_counters = iterator_counters("lead_", rate, lead_start),
        row_load_delay = t.row_load_delay,
        row_read = (t.row_lead + t.row_load_delay).saturating_sub(1),
        row_lead = t.row_lead,
    )
    .ok();

    // Primary ray.
    let pr_ports = block_ports("primary_ray")?;
    body += &instance(
        pr_ports,
        "primary_ray",
        "ray",
        "primary_ray",
        &|p| match p {
            "clk" => Some("clk".into()),
            "in_valid" => Some("issue".into()),
            "row_load" => Some("row_load".into()),
            "in_j" => Some("col_f".into()),
            _ => None,
        },
        &mut memory_ports,
        &mut decls,
    )?;
    writeln!(
        body,
        r#"    // The ray is ready {l_ray} cycles after its issue and held for the pixel's slots.
    wire ray_ready;
    fp_delay #(.WIDTH(1), .LATENCY({l_ray})) ray_ready_line (.clk(clk), .d(issue), .q(ray_ready));
    reg [95:0] ray_held = 96'd0;
    wire [95:0] ray_now = ray_ready ? {{ray_out_0, ray_out_1, ray_out_2}} : ray_held;
    always @(posedge clk) ray_held <= ray_now;
    // Slots: valid, first, last, k; the memory address {l_mem} cycles before the ray.
    wire [18:0] slot_info = {{slot, k == 16'd0, last_k, k}};
    wire [18:0] slot_at_memory, slot_at_unit;
    fp_delay #(.WIDTH(19), .LATENCY({mem_lead})) slot_to_memory (.clk(clk), .d(slot_info), .q(slot_at_memory));
    fp_delay #(.WIDTH(19), .LATENCY({l_mem})) slot_to_unit (.clk(clk), .d(slot_at_memory), .q(slot_at_unit));
    wire unit_valid = slot_at_unit[18];
    wire unit_first = slot_at_unit[17];
    wire unit_last = slot_at_unit[16];
"#,
        mem_lead = l_ray - l_mem,
    )
    .ok();

    // K intersection units, each with its minimum-distance block.
    let int_ports = block_ports("intersection")?;
    for u in 0..t.units {
        writeln!(
            body,
            r#"    // Unit {u}: primitives {u}·c … {u}·c + c − 1 (padding past n: a NaN centre hits nothing).
    wire [15:0] addr{u}_full = 16'd{u} * per_unit + slot_at_memory[15:0];
    wire [{a1}:0] addr{u} = addr{u}_full[{a1}:0];
    reg [{a1}:0] addr{u}_r1 = 0, addr{u}_r2 = 0;
    always @(posedge clk) begin addr{u}_r1 <= addr{u}; addr{u}_r2 <= addr{u}_r1; end
    // The padding flag of addr{u}_r2, registered beside it (compared on addr{u}_r1 a
    // cycle before): no compare between the registers and the unit's first stage.
    reg pad{u} = 1'b0;
    always @(posedge clk) pad{u} <= ({{{pad_zeros}'d0, addr{u}_r1}} >= prim_count);"#,
            a1 = ab - 1,
            pad_zeros = 16 - ab,
        )
        .ok();
        let mut unit_fields = BTreeMap::new();
        for (field, bits) in fields(false) {
            let q = format!("u{u}_f{field}");
            memory_ports.push((field, format!("addr{u}"), q.clone(), bits));
            unit_fields.insert(field, q);
        }
        let f = |i: u32| unit_fields.get(&i).cloned().unwrap_or_default();
        let connect = |p: &str| -> Option<String> {
            Some(match p {
                "clk" => "clk".into(),
                "in_valid" => "unit_valid".into(),
                "in_R_x" => "ray_now[95:64]".into(),
                "in_R_y" => "ray_now[63:32]".into(),
                "in_R_z" => "ray_now[31:0]".into(),
                "in_O_x" => "ray_now[95:64]".into(),
                "in_O_y" => "ray_now[63:32]".into(),
                "in_O_z" => "ray_now[31:0]".into(),
                "in_C_x" => format!("pad{u} ? 32'h7FC00000 : {}", f(0)),
                "in_C_y" => f(1),
                "in_C_z" => f(2),
                "in_r" => f(3),
                "in_V_x" => f(4),
                "in_V_y" => f(5),
                "in_V_z" => f(6),
                "in_Mmax" => f(7),
                "in_type" => format!("pad{u} ? 1'b0 : {}", f(8)),
                "in_address" => format!("addr{u}_r2"),
                _ => return None,
            })
        };
        body += &instance(
            int_ports,
            "intersection",
            &format!("unit{u}"),
            "intersection",
            &connect,
            &mut memory_ports,
            &mut decls,
        )?;
        writeln!(
            body,
            r#"    wire [2:0] unit{u}_flags;
    fp_delay #(.WIDTH(3), .LATENCY({l_int})) unit{u}_flag_line (.clk(clk), .d({{unit_valid, unit_first, unit_last}}), .q(unit{u}_flags));
    wire [31:0] min{u}_out_0, min{u}_out_1, min{u}_out_2, min{u}_out_3, min{u}_out_4;
    wire [{a1}:0] min{u}_out_5;
    wire min{u}_out_valid;
    min_distance min{u} (
        .clk(clk), .in_valid(unit{u}_flags[2]), .in_first(unit{u}_flags[1]), .in_last(unit{u}_flags[0]),
        .in_distance(unit{u}_out_0), .in_P_x(unit{u}_out_1), .in_P_y(unit{u}_out_2), .in_P_z(unit{u}_out_3),
        .in_m(unit{u}_out_4), .in_address(unit{u}_out_5),
        .out_0(min{u}_out_0), .out_1(min{u}_out_1), .out_2(min{u}_out_2), .out_3(min{u}_out_3),
        .out_4(min{u}_out_4), .out_5(min{u}_out_5), .out_valid(min{u}_out_valid)
    );"#,
            a1 = ab - 1,
        )
        .ok();
    }

    // The tree joining the units' minima.
    let (nearest, nearest_valid) = if let Some(tree) = &pipeline.min_tree {
        let tree_ports = block_ports("min_tree")?;
        let connect = |p: &str| -> Option<String> {
            if p == "clk" {
                return Some("clk".into());
            }
            if p == "in_valid" {
                return Some("min0_out_valid".into());
            }
            let rest = p.strip_prefix("in_")?;
            let digits = |s: &str| s.parse::<u32>().ok();
            let (unit, slot) = if let Some(u) = rest.strip_prefix("distance") {
                (digits(u)?, 0)
            } else if let Some(u) = rest.strip_prefix("address") {
                (digits(u)?, 5)
            } else if let Some(u) = rest.strip_prefix('m') {
                (digits(u)?, 4)
            } else if let Some(u) = rest.strip_prefix('P') {
                let (u, axis) = u.split_once('_')?;
                (
                    digits(u)?,
                    1 + ["x", "y", "z"].iter().position(|a| *a == axis)?,
                )
            } else {
                return None;
            };
            Some(format!("min{unit}_out_{slot}"))
        };
        let _ = tree;
        body += &instance(
            tree_ports,
            "min_tree",
            "tree",
            "min_tree",
            &connect,
            &mut memory_ports,
            &mut decls,
        )?;
        writeln!(
            body,
            "    wire tree_valid;\n    fp_delay #(.WIDTH(1), .LATENCY({l_tree})) tree_valid_line (.clk(clk), .d(min0_out_valid), .q(tree_valid));"
        )
        .ok();
        ("tree_out", "tree_valid")
    } else {
        ("min0_out", "min0_out_valid")
    };

    // Shading.
    let sh_ports = block_ports("shading")?;
    let connect = |p: &str| -> Option<String> {
        Some(match p {
            "clk" => "clk".into(),
            "in_valid" => nearest_valid.into(),
            "in_distance" => format!("{nearest}_0"),
            "in_P_x" => format!("{nearest}_1"),
            "in_P_y" => format!("{nearest}_2"),
            "in_P_z" => format!("{nearest}_3"),
            "in_address" => format!("{nearest}_5"),
            _ => return None,
        })
    };
    body += &instance(
        sh_ports,
        "shading",
        "shade",
        "shading",
        &connect,
        &mut memory_ports,
        &mut decls,
    )?;
    writeln!(
        body,
        r#"    // The frame-buffer write port: one gray level per pixel, in issue order.
    wire pixel_ready;
    fp_delay #(.WIDTH(1), .LATENCY({l_shade})) pixel_ready_line (.clk(clk), .d({nearest_valid}), .q(pixel_ready));
    reg [31:0] written = 32'd0;
    always @(posedge clk) if (pixel_ready) written <= written + 32'd1;
    assign fb_we = pixel_ready;
    assign fb_addr = written;
    assign fb_data = shade_out_0;
    assign done = finished & (written == issued);
    // Monitors: each block's input and output valid (bit: 0 ray, 1 unit 0, 2 minimum
    // distance 0 (its input: a pixel's last primitive), 3 tree, 4 shading).
    assign mon_in = {{3'd0, {nearest_valid}, {tree_in}, unit0_flags[2] & unit0_flags[0], unit_valid, issue}};
    assign mon_out = {{3'd0, shade_out_valid, {tree_out}, min0_out_valid, unit0_out_valid, ray_out_valid}};
"#,
        tree_in = if pipeline.min_tree.is_some() {
            "min0_out_valid"
        } else {
            "1'b0"
        },
        tree_out = if pipeline.min_tree.is_some() {
            "tree_out_valid"
        } else {
            "1'b0"
        },
    )
    .ok();
    let _ = l_min;

    // Scene memory: one RAM per word, a loader write port, 2-cycle read ports.
    let mut memory = String::new();
    writeln!(
        memory,
        "    // Scene memory: 2^{db} primitives, one RAM per word (thesis 6.1.1), written by\n    // the loader; each read port registers its address and its word ({l_mem} cycles).",
        db = t.depth_bits
    )
    .ok();
    let all_fields = fields(design.no_rsqrt_shading);
    for (field, bits) in &all_fields {
        writeln!(
            memory,
            "    reg [{b1}:0] scene_f{field} [0:{d1}];\n    always @(posedge clk) if (load_we && load_field == 4'd{field}) scene_f{field}[load_addr[{db1}:0]] <= load_data[{b1}:0];",
            b1 = bits - 1,
            d1 = (1u32 << t.depth_bits) - 1,
            db1 = t.depth_bits - 1,
        )
        .ok();
    }
    for (i, (field, addr, q, bits)) in memory_ports.iter().enumerate() {
        if !all_fields.iter().any(|(f, _)| f == field) {
            return Err(RtlError::Generate(format!(
                "a block reads scene word {field}, which this design does not store"
            )));
        }
        writeln!(
            memory,
            "    reg [{db1}:0] port{i}_a = 0;\n    reg [{b1}:0] {q} = 0;\n    always @(posedge clk) begin port{i}_a <= {addr}[{db1}:0]; {q} <= scene_f{field}[port{i}_a]; end",
            db1 = t.depth_bits - 1,
            b1 = bits - 1,
        )
        .ok();
    }

    Ok(format!(
        "// Generated by rtprof: the {label} pipeline, {units} intersection unit(s).\n// Latencies (model schedule): primary ray {l_ray}, intersection {l_int}, minimum distance {l_min}, tree {l_tree}, shading {l_shade}.\nmodule {TOP} (\n    {ports}\n);\n{decls}{body}{memory}endmodule\n",
        label = design.label(),
        units = t.units,
        ports = ports.join(",\n    "),
    ))
}
