//! `mason.Wall`: a wall design read by `mason_io::load_wall`, as `mason wall show` reads it.

use crate::{bad, input_error, to_py};
use mason_io::{Format, Sizes};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::sync::Arc;

/// A wall design: its bricks, their supports (the precedence DAG) and neighbours.
///
/// Make one with `Wall.load(path)` or `Wall.builtin(name)`. `len(wall)` is its brick count.
#[pyclass(module = "mason", name = "Wall", frozen)]
pub struct PyWall {
    pub(crate) wall: Arc<mason_wall::Wall>,
    warnings: Vec<String>,
}

fn format_of(py: Python<'_>, s: &str) -> PyResult<Format> {
    Ok(match s {
        "auto" => Format::Auto,
        "text" => Format::Text,
        "mbzirc" => Format::Mbzirc,
        "png" => Format::Png,
        "cmcp" => Format::Cmcp,
        other => {
            return Err(input_error(
                py,
                format!("format {other:?}: expected auto, text, mbzirc, png or cmcp"),
            ))
        }
    })
}

fn sizes_of(py: Python<'_>, s: &str) -> PyResult<Sizes> {
    match s {
        "yaml" => Ok(Sizes::Yaml),
        "swapped" => Ok(Sizes::Swapped),
        other => Err(input_error(
            py,
            format!("cmcp_sizes {other:?}: expected yaml or swapped"),
        )),
    }
}

#[pymethods]
impl PyWall {
    /// Reads a wall design file: layer text, the MBZIRC 21-token pattern, a PNG drawing or a
    /// CMCP `.txt` wall (`format="auto"` tells them apart). `cmcp_sizes` is `"yaml"` or
    /// `"swapped"`; with `strict=True` a CMCP wall's floating or overlapping bricks are errors.
    /// Bad input raises `mason.InputError` naming the file and the line or pixel.
    #[staticmethod]
    #[pyo3(signature = (path, format = "auto", cmcp_sizes = "yaml", strict = false))]
    fn load(
        py: Python<'_>,
        path: std::path::PathBuf,
        format: &str,
        cmcp_sizes: &str,
        strict: bool,
    ) -> PyResult<Self> {
        let format = format_of(py, format)?;
        let sizes = sizes_of(py, cmcp_sizes)?;
        let design = path.to_string_lossy().into_owned();
        let loaded = py
            .detach(|| mason_io::load_wall(&design, format, sizes, strict))
            .map_err(bad(py))?;
        Ok(PyWall {
            wall: Arc::new(loaded.wall),
            warnings: loaded.warnings,
        })
    }

    /// A built-in wall: `thesis-2x5`, `levels5-width5`, `levels5-width10` or `mbzirc` (see
    /// `mason.builtin_walls()`).
    #[staticmethod]
    fn builtin(py: Python<'_>, name: &str) -> PyResult<Self> {
        let loaded =
            mason_io::load_wall(&format!("builtin:{name}"), Format::Auto, Sizes::Yaml, false)
                .map_err(bad(py))?;
        Ok(PyWall {
            wall: Arc::new(loaded.wall),
            warnings: loaded.warnings,
        })
    }

    fn __len__(&self) -> usize {
        self.wall.len()
    }

    fn __repr__(&self) -> String {
        format!(
            "<mason.Wall {:?}: {} bricks, {} levels>",
            self.wall.name(),
            self.wall.len(),
            self.wall.levels()
        )
    }

    /// The wall's name (the file name, or the built-in's).
    #[getter]
    fn name(&self) -> String {
        self.wall.name().to_string()
    }

    /// Number of levels.
    #[getter]
    fn levels(&self) -> u32 {
        self.wall.levels()
    }

    /// What the reader warned about (floating or overlapping CMCP bricks), one line each.
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.warnings.clone()
    }

    /// The bricks, bottom level first: dicts with `id` (the thesis id, or the CMCP file's),
    /// `type`, `level`, `segment`, `x` and `y` (the footprint's centre, m), `footprint`
    /// (`[x0, x1, y0, y1]`), `supports` and `neighbours` (ids).
    #[getter]
    fn bricks<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let bricks = to_py(py, &mason_report::wall_json(&self.wall)["bricks"])?;
        for (item, id) in bricks.try_iter()?.zip(self.wall.ids()) {
            let f = self.wall.brick(id).footprint;
            let d = item?.cast_into::<PyDict>()?;
            d.set_item("x", 0.5 * (f.x0 + f.x1))?;
            d.set_item("y", 0.5 * (f.y0 + f.y1))?;
        }
        Ok(bricks)
    }

    /// The wall as the JSON `mason wall show --json` prints.
    fn to_json(&self) -> String {
        serde_json::to_string_pretty(&mason_report::wall_json(&self.wall)).unwrap_or_default()
    }

    /// The wall as an SVG figure (with `order`, a list of brick ids, numbered in that order).
    #[pyo3(signature = (order = None))]
    fn svg(&self, py: Python<'_>, order: Option<Vec<i64>>) -> PyResult<String> {
        let order = match order {
            Some(ids) => Some(crate::plans::brick_ids(py, &self.wall, &ids)?),
            None => None,
        };
        Ok(mason_report::wall_svg(&self.wall, order.as_deref()))
    }
}

/// The names of the built-in walls.
#[pyfunction]
fn builtin_walls() -> Vec<&'static str> {
    mason_wall::BUILTIN_WALLS.iter().map(|b| b.name).collect()
}

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyWall>()?;
    m.add_function(wrap_pyfunction!(builtin_walls, m)?)?;
    Ok(())
}
