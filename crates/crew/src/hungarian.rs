//! The Hungarian method (Kuhn 1955; Munkres 1957) in its O(n²·m) shortest-augmenting-path form
//! with row and column potentials. It assigns n rows to distinct columns among m ≥ n at the
//! least total cost. Optimal.

/// The column of each row in a least-cost assignment of `cost` (n rows of m ≥ n finite
/// entries each). Ties go to the first optimum the augmentation reaches.
pub fn hungarian(cost: &[Vec<f64>]) -> Vec<usize> {
    let n = cost.len();
    if n == 0 {
        return Vec::new();
    }
    let m = cost[0].len();
    assert!(m >= n, "more rows than columns");
    // 1-based arrays; column 0 is the virtual start of each augmenting path.
    let mut u = vec![0.0f64; n + 1];
    let mut v = vec![0.0f64; m + 1];
    let mut row_of = vec![0usize; m + 1];
    let mut way = vec![0usize; m + 1];
    for i in 1..=n {
        row_of[0] = i;
        let mut j0 = 0;
        let mut min_to = vec![f64::INFINITY; m + 1];
        let mut used = vec![false; m + 1];
        loop {
            used[j0] = true;
            let i0 = row_of[j0];
            let mut delta = f64::INFINITY;
            let mut j1 = 0;
            for j in 1..=m {
                if used[j] {
                    continue;
                }
                let reduced = cost[i0 - 1][j - 1] - u[i0] - v[j];
                if reduced < min_to[j] {
                    min_to[j] = reduced;
                    way[j] = j0;
                }
                if min_to[j] < delta {
                    delta = min_to[j];
                    j1 = j;
                }
            }
            for j in 0..=m {
                if used[j] {
                    u[row_of[j]] += delta;
                    v[j] -= delta;
                } else {
                    min_to[j] -= delta;
                }
            }
            j0 = j1;
            if row_of[j0] == 0 {
                break;
            }
        }
        loop {
            let j1 = way[j0];
            row_of[j0] = row_of[j1];
            j0 = j1;
            if j0 == 0 {
                break;
            }
        }
    }
    let mut col_of = vec![0usize; n];
    for j in 1..=m {
        if row_of[j] != 0 {
            col_of[row_of[j] - 1] = j - 1;
        }
    }
    col_of
}

/// The crew paper's Table 1 (Upadhyay et al. 2018): the distance from robot `R_j` (row) to
/// goal `G_i` (column) in its worked 8×8 example.
pub const PAPER_TABLE_1: [[f64; 3]; 3] = [[6.0, 7.0, 9.0], [7.0, 14.0, 10.0], [8.0, 7.0, 5.0]];

#[cfg(test)]
mod tests {
    use super::*;

    /// The paper's worked example: its best combination is R0→G1, R1→G0, R2→G2 with cost 19,
    /// and both Hungarian and the paper's own enumeration find it.
    #[test]
    fn the_papers_table_1_example() {
        let cost: Vec<Vec<f64>> = PAPER_TABLE_1.iter().map(|r| r.to_vec()).collect();
        for assignment in [hungarian(&cost), crate::perm::permutation_assignment(&cost)] {
            assert_eq!(assignment, vec![1, 0, 2]);
            let total: f64 = assignment
                .iter()
                .enumerate()
                .map(|(r, &g)| cost[r][g])
                .sum();
            assert_eq!(total, 19.0);
        }
    }

    #[test]
    fn small_square_and_rectangular() {
        let c = vec![
            vec![4.0, 1.0, 3.0],
            vec![2.0, 0.0, 5.0],
            vec![3.0, 2.0, 2.0],
        ];
        let a = hungarian(&c);
        let total: f64 = a.iter().enumerate().map(|(i, &j)| c[i][j]).sum();
        assert_eq!(total, 5.0);
        let r = vec![vec![9.0, 1.0, 9.0, 9.0], vec![1.0, 9.0, 9.0, 0.5]];
        assert_eq!(hungarian(&r), vec![1, 3]);
    }
}
