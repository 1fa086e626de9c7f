//! A plain, self-contained HTML report page: headed sections of HTML (inline SVG figures,
//! tables, links). Nothing is fetched from the network.

use crate::svg::escape;

/// One section of a report page.
pub struct Section {
    /// Heading.
    pub heading: String,
    /// HTML content (trusted: produced by Mason).
    pub html: String,
}

/// A report page.
pub fn report_page(title: &str, intro: &str, sections: &[Section]) -> String {
    let mut out = format!(
        "<!DOCTYPE html><html lang=\"en\"><head><meta charset=\"utf-8\"><title>{t}</title><style>\
body{{font-family:sans-serif;margin:24px auto;max-width:1150px;color:#222;background:#fafafa;line-height:1.4}}\
section{{background:#fff;border:1px solid #ddd;border-radius:6px;padding:12px 18px;margin:18px 0}}\
svg{{max-width:100%;height:auto}}pre{{background:#f3f3f3;padding:8px;overflow-x:auto;font-size:12px}}\
iframe{{width:100%;height:820px;border:1px solid #ccc}}nav a{{margin-right:14px}}</style></head><body><h1>{t}</h1><p>{i}</p><nav>",
        t = escape(title),
        i = escape(intro)
    );
    for (k, s) in sections.iter().enumerate() {
        out.push_str(&format!("<a href=\"#s{k}\">{}</a>", escape(&s.heading)));
    }
    out.push_str("</nav>");
    for (k, s) in sections.iter().enumerate() {
        out.push_str(&format!(
            "<section id=\"s{k}\"><h2>{}</h2>{}</section>",
            escape(&s.heading),
            s.html
        ));
    }
    out.push_str("</body></html>");
    out
}

/// Text shown as preformatted HTML.
pub fn pre(text: &str) -> String {
    format!("<pre>{}</pre>", escape(text))
}
