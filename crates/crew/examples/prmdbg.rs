use mason_crew::prm::*;
use mason_crew::*;
fn main() {
    for clutter in [0.0, 0.005, 0.01] {
        for samples in [2000, 4000, 8000] {
            let grid = mason_crew::generate::warehouse(450, 450, clutter, 1);
            let t = std::time::Instant::now();
            let map = Roadmap::build(
                &grid,
                Connectivity::Eight,
                PrmConfig {
                    samples,
                    neighbours: 10,
                    seed: 0,
                },
            );
            let bt = t.elapsed();
            let (r, g) = mason_crew::generate::random_tasks(&grid, 50, 3);
            let ok = (0..50)
                .filter(|&i| map.path(&grid, Connectivity::Eight, r[i], g[i]).0.is_some())
                .count();
            println!(
                "clutter {clutter} samples {samples}: edges {} ok {ok}/50 build {:?} total {:?}",
                map.edge_count(),
                bt,
                t.elapsed()
            );
        }
    }
}
