//! Material removal in the page (`vcnc sim`'s report, `docs/sim.md`): the
//! stock from the page's stock text (`--stock`'s syntax), else the CAM
//! header comment, else the automatic stock of a survey pass — the order
//! `vcnc sim` resolves it in — then one run into `vcnc_sim::Simulation`
//! on one worker (a page's worker is one thread), giving the removed
//! volume and the collisions at their lines, and (when asked) the stock
//! and the finished part as meshes for the page's viewer — the two
//! `vcnc plot --stock` draws (`vcnc_sim::mesh::stock_and_part`).

use crate::check::run;
use crate::setup::{DialectChoice, Settings, Setup};
use serde::Serialize;
use vcnc_sim::{SimOptions, Simulation, StockOrigin, StockSpec, Survey};

/// A collision of the simulation.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SimCollision {
    /// 1-based line of its block.
    pub line: u64,
    /// The file, when not the main program.
    pub file: Option<String>,
    /// `rapid_into_stock`, `holder`, `table` …
    pub kind: &'static str,
    /// What happened.
    pub message: String,
}

/// What [`sim`] found.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Simulated {
    /// The dialect and why.
    pub dialect: DialectChoice,
    /// The stock as used, in words.
    pub stock: String,
    /// The stock's volume, mm³.
    pub stock_mm3: f64,
    /// The volume removed, mm³.
    pub removed_mm3: f64,
    /// Time at feed that removed nothing, s.
    pub air_cut_s: f64,
    /// Collisions (at most `vcnc_sim`'s limit), in program order.
    pub collisions: Vec<SimCollision>,
    /// Collisions in all.
    pub collision_total: u64,
    /// Notes (assumed tools, the grid).
    pub notes: Vec<String>,
    /// The stock (hidden at first) and the finished part, as
    /// `vcnc_plot::meshes_data`'s JSON for the viewer, when asked for and
    /// something was simulated.
    pub meshes: Option<String>,
}

/// The viewer's meshes of a finished simulation: the stock, hidden at
/// first (it would hide the part), and the finished part — the colours
/// and order of `vcnc plot --stock`'s page.
fn meshes(part: &vcnc_sim::Part) -> Option<String> {
    let (stock, part) = vcnc_sim::mesh::stock_and_part(part)?;
    let mesh = |name: &str, color, visible, m: vcnc_sim::mesh::Indexed| vcnc_plot::Mesh {
        name: name.to_string(),
        color,
        visible,
        positions: m.positions,
        triangles: m.triangles,
    };
    Some(vcnc_plot::meshes_data(&[
        mesh("stock", vcnc_plot::Rgb(150, 165, 185), false, stock),
        mesh("finished part", vcnc_plot::Rgb(215, 150, 70), true, part),
    ]))
}

/// Simulates the material removal of `text` on `stock` (`--stock`'s
/// syntax; none: the header comment, else automatic); `with_meshes`: the
/// stock and the finished part for the viewer too.
pub fn sim(
    text: &str,
    settings: &Settings,
    stock: Option<&str>,
    with_meshes: bool,
) -> Result<Simulated, String> {
    let s = Setup::new(text, settings)?;
    let lathe = s.dialect.diameter.lathe;
    let (mut spec, mut origin) = match stock.map(str::trim).filter(|t| !t.is_empty()) {
        Some(t) => (StockSpec::parse(t)?, StockOrigin::Option),
        None => vcnc_sim::from_header(text).unwrap_or((StockSpec::Auto, StockOrigin::Auto)),
    };
    if lathe && matches!(spec, StockSpec::Box { .. }) && origin != StockOrigin::Option {
        // A mill post's header on a lathe program says nothing of its bar.
        (spec, origin) = (StockSpec::Auto, StockOrigin::Auto);
    }
    vcnc_sim::check_setup(&spec, None, lathe)?;
    if spec == StockSpec::Auto {
        let mut survey = Survey::new(&s.machine, &s.tools, lathe);
        run(text, &s, false, false, &mut survey);
        spec = survey
            .stock()
            .ok_or("the program cuts nothing: there is no stock to find")?;
        vcnc_sim::check_setup(&spec, None, lathe)
            .map_err(|e| format!("the automatic stock ({}): {e}", spec.describe()))?;
    }
    let options = SimOptions {
        stock: spec,
        stock_origin: origin,
        resolution_mm: None,
        lathe,
        workers: 1,
        replay: None,
    };
    let mut simulation = Simulation::new(&s.machine, &s.tools, s.machine.table_z_mm, options)?;
    run(text, &s, false, false, &mut simulation);
    let finished = simulation.finish_run()?;
    let meshes = if with_meshes {
        meshes(&finished.part)
    } else {
        None
    };
    let r = finished.report;
    Ok(Simulated {
        dialect: s.choice.clone(),
        stock: r.stock,
        stock_mm3: r.stock_mm3,
        removed_mm3: r.removed_mm3,
        air_cut_s: r.air_cut_s,
        collisions: r
            .collisions
            .iter()
            .map(|c| SimCollision {
                line: c.line,
                file: c.file.as_deref().map(str::to_string),
                kind: c.kind.as_str(),
                message: c.message.clone(),
            })
            .collect(),
        collision_total: r.collision_total,
        notes: r.notes,
        meshes,
    })
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    #[test]
    fn a_slot_removes_its_volume_and_a_rapid_into_the_stock_is_a_collision() {
        // A flat end mill of 10 mm along X from X0 to X50, 2 mm deep, in
        // a 100 x 100 x 20 block from X0 whose top is Z0: the slot is
        // 50 x 10 x 2 plus the half-disc at its far end, π·5²·2 / 2 (the
        // near one is outside the block).
        let tools = Settings {
            dialect: Some("fanuc".into()),
            tools: Some("T1 P1 D10.0 Z0 ;flat end mill\n".into()),
            tools_name: Some("t.tbl".into()),
            ..Settings::default()
        };
        let text =
            "T1 M06\nG90 G54 G00 X0 Y50. Z5. S5000 M03\nG01 Z-2. F100.\nX50.\nG00 Z5.\nM30\n";
        let r = sim(text, &tools, Some("box:0,0,-20,100,100,0"), true).unwrap();
        let slot = 50.0 * 10.0 * 2.0 + std::f64::consts::PI * 25.0;
        assert!(
            (r.removed_mm3 - slot).abs() / slot < 0.01,
            "{} vs {slot}",
            r.removed_mm3
        );
        assert_eq!(r.stock_mm3, 200_000.0);
        assert_eq!(r.collision_total, 0, "{:?}", r.collisions);
        // The stock and the part for the viewer, about the block's middle.
        let m: serde_json::Value = serde_json::from_str(r.meshes.as_deref().unwrap()).unwrap();
        assert_eq!(m["meshes"][0]["name"], "stock");
        assert_eq!(m["meshes"][0]["visible"], false);
        assert_eq!(m["meshes"][1]["name"], "finished part");
        assert!(m["meshes"][1]["tris"].as_u64().unwrap() > 12);
        for (k, c) in [50.0, 50.0, -10.0].into_iter().enumerate() {
            assert_eq!(m["center"][k], c, "{}", m["center"]);
        }
        let crash = "T1 M06\nG90 G54 G00 X0 Y50. Z5. S5000 M03\nG00 Z-2.\nM30\n";
        let r = sim(crash, &tools, Some("box:0,0,-20,100,100,0"), false).unwrap();
        assert!(r.meshes.is_none());
        assert_eq!(r.collisions.first().map(|c| c.line), Some(3), "{r:?}");
    }
}
