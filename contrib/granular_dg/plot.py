"""The matplotlib set-up of the figure scripts. matplotlib is imported when a
figure is made, so the readers work without it (Debian's python3-matplotlib:
run the scripts with /usr/bin/python3)."""
import os

from granular_dg import directory

STYLES = ["-", "--", ":", "-."]  # the line styles of runs drawn in black or one colour

def pyplot():
    """matplotlib.pyplot on the Agg backend; SVG files without a date and
    with fixed element ids, so charts of the same runs are byte-identical."""
    try:
        import matplotlib
    except ImportError:
        raise SystemExit("matplotlib is missing: run with /usr/bin/python3 (Debian's "
                         "python3-matplotlib, bash contrib/install-deps.sh --tests)") from None
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    plt.rcParams["svg.hashsalt"] = "granular_dg study"
    return plt


def subplots(*args, **kwargs):
    return pyplot().subplots(*args, **kwargs)


def save(fig, path, *formats, dpi=110, tight=True, say=False, **kwargs):
    """Writes the figure to PATH and beside it in the other formats ("svg"),
    then closes it."""
    if tight:
        fig.tight_layout()
    base, ext = os.path.splitext(path)
    for p in [path] + [base + "." + f for f in formats]:
        fig.savefig(p, dpi=dpi, metadata={"Date": None} if p.endswith(".svg") else None, **kwargs)
        if say:
            print("wrote " + p)
    pyplot().close(fig)


def label(ax, x=None, y=None, title=None, legend=None, size=None, grid=0.3, which="both"):
    """Axis labels, title (font size), grid (its alpha, which ticks) and
    legend (its font size, or (font size, columns))."""
    if x:
        ax.set_xlabel(x)
    if y:
        ax.set_ylabel(y)
    if title:
        ax.set_title(title, **({"fontsize": size} if size else {}))
    if grid:
        ax.grid(alpha=grid, which=which)
    if legend:
        font, ncol = legend if isinstance(legend, tuple) else (legend, 1)
        ax.legend(fontsize=font, ncol=ncol)


def log_ticks(ax, values):
    """A log x axis with ticks at the values run, written as plain numbers."""
    from matplotlib.ticker import FixedLocator, FormatStrFormatter, NullLocator
    ax.set_xscale("log")
    ax.xaxis.set(major_locator=FixedLocator(sorted(set(values))), major_formatter=FormatStrFormatter("%.3g"),
                 minor_locator=NullLocator())


def split_run(text):
    """'DIR:label' -> (DIR, label); the label defaults to DIR's last part."""
    d, _, name = text.partition(":")
    return directory(d), name or os.path.basename(os.path.normpath(d))
