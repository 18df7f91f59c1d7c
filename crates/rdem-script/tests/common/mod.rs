//! Helpers shared by the rdem-script test files.

use rdem_script::ScriptReport;

/// The report as text, without colour and wide enough that no line wraps.
pub fn render(r: &ScriptReport) -> String {
    let mut out = String::new();
    miette::GraphicalReportHandler::new_themed(miette::GraphicalTheme::unicode_nocolor())
        .with_width(10_000)
        .render_report(&mut out, r)
        .expect("render");
    out
}
