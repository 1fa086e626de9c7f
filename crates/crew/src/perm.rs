//! The crew paper's assignment: try every way to give the n robots distinct goals (n! of them
//! when there are as many goals as robots) and keep the least total cost. Optimal; O(n!·n).
//! Refused above [`PERM_LIMIT`] robots.

/// The most robots `perm` accepts (10! = 3 628 800 permutations).
pub const PERM_LIMIT: usize = 10;

/// The column of each row in a least-cost assignment, by exhaustive enumeration. Ties go to
/// the lexicographically first assignment.
pub fn permutation_assignment(cost: &[Vec<f64>]) -> Vec<usize> {
    let n = cost.len();
    if n == 0 {
        return Vec::new();
    }
    let m = cost[0].len();
    let mut best = (f64::INFINITY, Vec::new());
    let mut current = Vec::with_capacity(n);
    let mut used = vec![false; m];
    enumerate(cost, &mut current, &mut used, 0.0, &mut best);
    best.1
}

fn enumerate(
    cost: &[Vec<f64>],
    current: &mut Vec<usize>,
    used: &mut [bool],
    sum: f64,
    best: &mut (f64, Vec<usize>),
) {
    let row = current.len();
    if row == cost.len() {
        if sum < best.0 {
            *best = (sum, current.clone());
        }
        return;
    }
    for j in 0..used.len() {
        if !used[j] {
            used[j] = true;
            current.push(j);
            enumerate(cost, current, used, sum + cost[row][j], best);
            current.pop();
            used[j] = false;
        }
    }
}
