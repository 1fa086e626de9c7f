//! A build order read back: Mason's `plan --json` (its `order` of brick labels and its
//! `total_cost`) or a plain list of brick ids, separated by spaces, commas or newlines, with
//! `#` comments.

use super::json::{document, value, LineIndex};
use super::{at, looks_like_json, Labels};
use crate::error::InputResult;
use crate::files::{read_input_text, MAX_INPUT_BYTES};
use mason_wall::{BrickId, Wall};
use serde::Deserialize;
use serde_json::value::RawValue;
use std::path::Path;

/// A build order as read.
#[derive(Clone, Debug, PartialEq)]
pub struct OrderFile {
    /// The bricks in order.
    pub order: Vec<BrickId>,
    /// The total cost the file states (`plan --json`), if any.
    pub total_cost: Option<f64>,
    /// `plan --json` or `list`.
    pub format: &'static str,
}

#[derive(Deserialize)]
struct PlanJson<'a> {
    #[serde(borrow)]
    order: Option<Vec<&'a RawValue>>,
    total_cost: Option<f64>,
}

/// Reads `path` ([`parse_order`]).
pub fn read_order(path: &Path, wall: &Wall) -> InputResult<OrderFile> {
    parse_order(&read_input_text(path, MAX_INPUT_BYTES)?, path, wall)
}

/// The order in `text` (from `path`, named in errors): a JSON object with an `order` list of
/// brick labels, or a plain list of labels. A label that is not in `wall` is an error naming
/// its line.
pub fn parse_order(text: &str, path: &Path, wall: &Wall) -> InputResult<OrderFile> {
    let labels = Labels::new(wall);
    if looks_like_json(text) {
        let plan: PlanJson<'_> = document(text, path)?;
        let lines = LineIndex::new(text);
        let Some(order) = plan.order else {
            return Err(at(path, 1, "no `order` (a plan that found none?)"));
        };
        let order = order
            .iter()
            .map(|raw| labels.brick(value::<u32>(text, raw, path)?, path, lines.of(raw.get())))
            .collect::<InputResult<Vec<_>>>()?;
        return Ok(OrderFile {
            order,
            total_cost: plan.total_cost,
            format: "plan --json",
        });
    }
    let mut order = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let content = line.split('#').next().unwrap_or("");
        for token in content
            .split(|c: char| c == ',' || c.is_whitespace())
            .filter(|t| !t.is_empty())
        {
            let label: u32 = token
                .parse()
                .map_err(|_| at(path, i + 1, format!("`{token}` is not a brick id")))?;
            order.push(labels.brick(label, path, i + 1)?);
        }
    }
    if order.is_empty() {
        return Err(at(
            path,
            1,
            "no brick ids (expected ids separated by spaces, commas or newlines)",
        ));
    }
    Ok(OrderFile {
        order,
        total_cost: None,
        format: "list",
    })
}

impl OrderFile {
    /// Checks the order with `order::validate` and, when the file states a total cost, that
    /// claim: the evaluation, or the broken rules (the first one; with `all`, every one).
    pub fn check(
        &self,
        wall: &Wall,
        model: &mason_order::CostModel,
        all: bool,
    ) -> Result<mason_order::Evaluation, Vec<mason_order::OrderError>> {
        let eval = match mason_order::validate(wall, model, &self.order) {
            Ok(eval) => eval,
            Err(first) if !all => return Err(vec![first]),
            Err(_) => return Err(mason_order::order_violations(wall, model, &self.order)),
        };
        match self.total_cost {
            Some(claimed) => mason_order::validate_claim(wall, model, &self.order, claimed)
                .map(|_| eval)
                .map_err(|e| vec![e]),
            None => Ok(eval),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn wall() -> Wall {
        mason_wall::builtin("thesis-2x5").unwrap().wall()
    }

    #[test]
    fn a_list_with_commas_newlines_and_comments() {
        let w = wall();
        let f = parse_order(
            "101, 102 103 # first three\n\n104,105\n",
            Path::new("o.txt"),
            &w,
        )
        .unwrap();
        let labels: Vec<u32> = f.order.iter().map(|&b| w.brick(b).label).collect();
        assert_eq!(labels, [101, 102, 103, 104, 105]);
        assert_eq!(f.format, "list");
    }

    #[test]
    fn bad_ids_name_the_file_and_line() {
        let w = wall();
        let e = parse_order("101\n102 x\n", Path::new("o.txt"), &w)
            .unwrap_err()
            .to_string();
        assert_eq!(e, "o.txt:2: `x` is not a brick id");
        let e = parse_order("101\n\n999\n", Path::new("o.txt"), &w)
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("o.txt:3: brick 999 is not in the wall"),
            "{e}"
        );
        let e = parse_order("# nothing\n", Path::new("o.txt"), &w)
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("o.txt:1: no brick ids"), "{e}");
    }

    #[test]
    fn json_labels_and_their_lines() {
        let w = wall();
        let f = parse_order(
            "{\"order\": [101,\n 102], \"total_cost\": 5.5}",
            Path::new("p.json"),
            &w,
        )
        .unwrap();
        assert_eq!(f.order.len(), 2);
        assert_eq!(f.total_cost, Some(5.5));
        let e = parse_order("{\"order\": [101,\n 777]}", Path::new("p.json"), &w)
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("p.json:2: brick 777"), "{e}");
        let e = parse_order("{\"order\": [101,\n\n \"a\"]}", Path::new("p.json"), &w)
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("p.json:3: invalid type"), "{e}");
        let e = parse_order("{\"order\": [101,", Path::new("p.json"), &w)
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("p.json:1: "), "{e}");
    }
}
