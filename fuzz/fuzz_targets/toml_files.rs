//! The TOML files: cost model (`--model`), mission (`--mission`, with its `[faults]` table) and
//! team model (`plan --objective --model`), the faults file (`simulate --faults`) and the
//! agents' network file (`agent --config`), each parsed and then validated.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    if let Ok(model) = toml::from_str::<mason_order::CostModel>(text) {
        if model.validate().is_ok() {
            let wall = mason_wall::builtin("thesis-2x5").expect("built-in").wall();
            let problem = mason_order::BuildProblem::new(&wall, model).expect("validated");
            let out =
                mason_order::PlannerSpec::Greedy.plan(&problem, &mason_order::Budget::unlimited());
            assert!(out.total_cost.is_some_and(f64::is_finite));
        }
    }
    if let Ok(config) = toml::from_str::<mason_mission::MissionConfig>(text) {
        let _ = config.validate();
    }
    if let Ok(patch) = toml::from_str::<mason_order::schedule::TeamModelPatch>(text) {
        let _ = mason_order::schedule::TeamModel::from_patch(&patch, "fuzz");
    }
    if let Ok(spec) = toml::from_str::<mason_io::FaultSpec>(text) {
        if let Ok(faults) = spec.resolve() {
            let config = mason_mission::MissionConfig {
                faults,
                ..mason_mission::MissionConfig::with_uavs(3)
            };
            let _ = config.validate();
        }
    }
    if let Ok(net) = toml::from_str::<mason_fleet::NetworkFile>(text) {
        for e in &net.listen {
            let _ = mason_fleet::check_endpoint("--listen", e, true);
        }
        for e in &net.connect {
            let _ = mason_fleet::check_endpoint("--connect", e, false);
        }
        if let Some(m) = &net.mission {
            let _ = mason_fleet::check_chunks("--mission", m, true);
        }
        if let Some(p) = &net.prefix {
            let _ = mason_fleet::check_chunks("--prefix", p, false);
        }
    }
});
