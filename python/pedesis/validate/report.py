"""The results of `pedesis validate`: a table on the console and a Markdown report with a
figure per case."""
import math
import os
from pathlib import Path


def value_text(value, error):
    """value ± error with the error to two significant digits (value alone if error is 0)."""
    if not math.isfinite(value):
        return str(value)
    if not math.isfinite(error):
        return f"{value:.5g} (no error estimate)"
    if not error > 0:
        return f"{value:.5g}"
    digits = max(0, 1 - int(math.floor(math.log10(error))))
    return f"{value:.{digits}f} ± {error:.{digits}f}"


def rows(results):
    """(case, quantity, measured, reference, source, verdict) for every check, and a row
    for each case that could not measure."""
    out = []
    for r in results:
        if r.error is not None:
            out.append((r.name, "(the case could not measure)", "-", "-", r.error, "FAIL"))
        for c in r.checks:
            out.append((r.name, c.quantity, value_text(c.measured, c.error), c.reference,
                        c.source, c.verdict))
    return out


def console_table(results):
    """The table printed at the end of a run."""
    table = rows(results)
    header = ("case", "quantity", "measured", "reference", "source", "result")
    widths = [max(len(str(x[k])) for x in table + [header]) for k in range(5)]
    lines = ["  ".join(str(x[k]).ljust(widths[k]) for k in range(5)) + "  " + x[5]
             for x in [header] + table]
    lines.insert(1, "-" * len(lines[0]))
    return "\n".join(lines)


def _escape(text):
    return str(text).replace("|", "\\|")


def write_report(results, out, mode, seconds, machine):
    """out/report.md (written to a temporary name, then renamed) and out/figures/*.png."""
    out = Path(out)
    figures = out / "figures"
    figures.mkdir(parents=True, exist_ok=True)
    drawn = _draw_figures(results, figures)
    passed = sum(r.passed for r in results)
    text = [f"# pedesis validate{' --quick' if mode == 'quick' else ''}", "",
            f"{passed} of {len(results)} cases passed in {seconds:.0f} s on {machine}.", "",
            "| case | quantity | measured ± standard error | reference | source | result |",
            "|---|---|---|---|---|---|"]
    text += ["| " + " | ".join(_escape(x) for x in row) + " |" for row in rows(results)]
    for r in results:
        text += ["", f"## {r.title} (`{r.name}`)", "", f"Ran: {r.ran}.", ""]
        if r.error is not None:
            text += [f"**The case could not measure:** {r.error}", ""]
        for c in r.checks:
            text.append(f"- **{c.quantity}**: {value_text(c.measured, c.error)} against "
                        f"{c.reference} ({c.source}): **{c.verdict}**. Why this tolerance: {c.why}.")
        if r.name in drawn:
            text += ["", f"![{r.title}](figures/{r.name}.png)"]
    report = out / "report.md"
    partial = out / "report.md.part"
    partial.write_text("\n".join(text) + "\n")
    os.replace(partial, report)
    return report


def _draw_figures(results, folder):
    """A PNG per case that has a plot; the names of the cases drawn."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    drawn = set()
    for r in results:
        if r.plot is None or r.error is not None:
            continue
        fig, ax = plt.subplots(figsize=(5.0, 3.6))
        r.plot(ax)
        ax.set_title(r.title, fontsize=10)
        fig.tight_layout()
        partial = folder / f"{r.name}.part.png"
        fig.savefig(partial, dpi=100)
        plt.close(fig)
        os.replace(partial, folder / f"{r.name}.png")
        drawn.add(r.name)
    return drawn
