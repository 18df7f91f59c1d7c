//! `group`: named sets of particles (at most 32, `all` included).

use crate::args::{Args, CmdResult};
use crate::sim::Sim;

pub(super) fn group(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let name = a.word("group ID")?.to_string();
    const STYLES: [&str; 7] = [
        "region",
        "type",
        "id",
        "union",
        "subtract",
        "intersect",
        "delete",
    ];
    let style = a.keyword("group style", &STYLES)?;
    if style == "delete" {
        a.done()?;
        let k = sim
            .defs
            .groups
            .find(&name)
            .ok_or_else(|| a.error_at(1, format!("no group '{name}'"), None))?;
        if k == 0 {
            return Err(a.error_at(1, "group all cannot be deleted", None));
        }
        if let Some(w) = &mut sim.world {
            for m in &mut w.particles.mask {
                *m &= !(1u32 << k);
            }
        }
        sim.defs.groups.delete(k);
        return Ok(());
    }
    if name == "all" {
        return Err(a.error_at(1, "group all cannot be changed", None));
    }
    let n = sim.world_ref(a)?.particles.nlocal();
    let sel: Vec<bool> = match style {
        "region" => {
            let r = sim.region(a)?;
            a.done()?;
            let p = &sim.world.as_ref().expect("checked").particles;
            (0..n).map(|i| r.contains(p.x[i])).collect()
        }
        "type" | "id" => {
            let mut sel = vec![false; n];
            if a.is_done() {
                return Err(a.error_at(a.pos(), format!("group {style}: missing values"), None));
            }
            while let Some(spec) = a.peek() {
                let at = a.pos();
                let (lo, hi) = match spec.split_once(':') {
                    Some((l, h)) => match (a.integer_in(at, l), a.integer_in(at, h)) {
                        (Some(l), Some(h)) => (l, h),
                        _ => return Err(a.error_at(a.pos(), format!("bad range '{spec}'"), None)),
                    },
                    None => match a.integer_in(at, spec) {
                        Some(v) => (v, v),
                        None => {
                            return Err(a.error_at(
                                a.pos(),
                                format!("'{spec}' is not a number or range a:b"),
                                None,
                            ))
                        }
                    },
                };
                a.seek(a.pos() + 1);
                let p = &sim.world.as_ref().expect("checked").particles;
                for (i, s) in sel.iter_mut().enumerate() {
                    let v = if style == "type" {
                        p.ty[i] as u64
                    } else {
                        p.tag[i]
                    };
                    if v >= lo && v <= hi {
                        *s = true;
                    }
                }
            }
            sel
        }
        _ => {
            let mut bits = Vec::new();
            while !a.is_done() {
                bits.push(sim.group_bit(a, "group ID")?);
            }
            if bits.is_empty() {
                return Err(a.error_at(
                    a.pos(),
                    format!("group {style}: needs at least one group"),
                    None,
                ));
            }
            let p = &sim.world.as_ref().expect("checked").particles;
            (0..n)
                .map(|i| {
                    let m = p.mask[i];
                    match style {
                        "union" => bits.iter().any(|b| m & b != 0),
                        "intersect" => bits.iter().all(|b| m & b != 0),
                        _ => m & bits[0] != 0 && bits[1..].iter().all(|b| m & b == 0),
                    }
                })
                .collect()
        }
    };
    let k = sim
        .defs
        .groups
        .find_or_create(&name)
        .map_err(|m| a.error_at(1, m, None))?;
    let w = sim.world.as_mut().expect("checked");
    let mut count = 0;
    for (i, s) in sel.iter().enumerate() {
        if *s {
            w.particles.mask[i] |= 1 << k;
        }
        if w.particles.mask[i] & (1 << k) != 0 {
            count += 1;
        }
    }
    let count = w.comm.sum_count(count);
    sim.outputs
        .out
        .line(&format!("{count} atoms in group {name}"));
    Ok(())
}
