#!/usr/bin/env python3
"""fe bench's charts and report (called by `fe bench`, or by hand: report.py DIR/results.json).

Reads results.json and writes beside it charts/*.png and charts/*.svg (Debian's
python3-matplotlib) and report.html: the charts, then per case a row of every backend's image,
FLIP heat map against the exact reference and metrics. Every chart names its axes, units and
devices, and says when a device is a software rasterizer.

Readability: a technique has one colour, marker and line style on every chart (TECHNIQUE_STYLES),
named in a legend beside the plots (never text at the data points); an axis whose values are all
positive and span more than a decade (LOG_SPAN) is logarithmic, with plain-number ticks (base 2 for
light and sample counts); the report page shows the heaviest cases first (weight()).
"""
import html
import json
import math
import os
import sys
import urllib.parse
import zlib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib import ticker  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402

# An axis is logarithmic when its values are all positive and the largest is more than LOG_SPAN
# times the smallest (frame times from 9 to 1700 ms, 64 to 4096 lights); otherwise linear.
LOG_SPAN = 10

# Technique -> (colour, marker, line style), the same on every chart: the forward family solid,
# the deferred family dashed, light pre-pass dotted, the redeferred ones dash-dotted. A technique
# not listed gets a style from FALLBACK_COLOURS x FALLBACK_MARKERS by a hash of its name.
TECHNIQUE_STYLES = {
    "forward": ("#1f77b4", "o", "-"),
    "forward-multipass": ("#17becf", "v", "-"),
    "forward-zprepass": ("#9467bd", "s", "-"),
    "forward-plus": ("#ff7f0e", "P", "-"),
    "clustered-forward": ("#d62728", "X", "-"),
    "deferred": ("#2ca02c", "D", "--"),
    "deferred-tiled": ("#8c564b", "^", "--"),
    "clustered-deferred": ("#e377c2", "*", "--"),
    "visibility-buffer": ("#e6550d", "d", (0, (5, 1, 1, 1))),
    "light-prepass": ("#7f7f7f", "p", ":"),
    "light-prepass-unpacked": ("#bcbd22", "h", ":"),
    "redeferred": ("#000000", "<", "-."),
    "redeferred-tiled": ("#393b79", ">", "-."),
}
FALLBACK_COLOURS = ("#843c39", "#637939", "#7b4173", "#3182bd", "#e6550d", "#31a354", "#756bb1", "#636363")
FALLBACK_MARKERS = ("d", "H", "8", "o", "s", "^", "v", "D")
# A technique's variants on one chart (MSAA, illumination scale, tone mapper...): its marker,
# filled in these ways, in the order the variants first appear.
VARIANT_FILLS = ("full", "none", "left", "bottom", "right", "top")


def slug(text):
    return "".join(c if c.isalnum() or c == "-" else "_" for c in text).strip("_")


def technique_style(t):
    if t in TECHNIQUE_STYLES:
        return TECHNIQUE_STYLES[t]
    h = zlib.crc32(t.encode())
    return FALLBACK_COLOURS[h % len(FALLBACK_COLOURS)], FALLBACK_MARKERS[(h // 8) % len(FALLBACK_MARKERS)], "-"


def technique_order(techniques):
    """The techniques in TECHNIQUE_STYLES' order, any others after them by name."""
    known = list(TECHNIQUE_STYLES)
    return sorted(set(techniques), key=lambda t: (known.index(t) if t in known else len(known), t))


def weight(rows):
    """The report's order: a chart (or case) of heavier cases comes first. A case's weight is its
    light count (at least 1) times its pixels; a chart's, its heaviest case's. So the many-light
    sweeps (4096 lights at 640x360) open the page and the quick sweep's 96x72 cases close it."""
    return max((max(r["settings"].get("lights", 0), 1) * r["settings"].get("width", 1) * r["settings"].get("height", 1)
                for r in rows), default=0)


def scale_axis(ax, which, values, count=False):
    """Logarithmic when the values are all positive and span more than LOG_SPAN (base 2 for counts:
    lights, samples), with plain-number tick labels; counts get a tick at each value when there are few."""
    vals = [v for v in values if v is not None and math.isfinite(v)]
    axis = ax.xaxis if which == "x" else ax.yaxis
    log = bool(vals) and min(vals) > 0 and max(vals) / min(vals) > LOG_SPAN
    if log:
        (ax.set_xscale if which == "x" else ax.set_yscale)("log", base=2 if count else 10)
        if not count:
            decades = math.log10(max(vals) / min(vals))
            axis.set_major_locator(ticker.LogLocator(base=10, subs=(1.0, 2.0, 5.0) if decades <= 3 else (1.0,)))
            axis.set_minor_locator(ticker.LogLocator(base=10, subs=tuple(range(2, 10))))
            axis.set_minor_formatter(ticker.NullFormatter())
        axis.set_major_formatter(ticker.FuncFormatter(lambda v, _: f"{v:g}"))
    if count and vals:
        distinct = sorted(set(vals))
        if len(distinct) <= 12:
            axis.set_major_locator(ticker.FixedLocator(distinct))
            axis.set_major_formatter(ticker.FuncFormatter(lambda v, _: f"{v:g}"))
        axis.set_minor_locator(ticker.NullLocator())
    return log


def technique_handle(t, line=True):
    colour, marker, style = technique_style(t)
    return Line2D([], [], color=colour, marker=marker, linestyle=style if line else "none", markersize=7, label=t)


def figure_legend(fig, axes, handles, title):
    """One legend for the figure, outside the plots on the right (the figure's image grows to hold
    it), level with the top row; none when there is nothing to name."""
    if not handles:
        return
    right = max(ax.get_position().x1 for ax in axes)
    top = max(ax.get_position().y1 for ax in axes)
    fig.legend(handles=handles, labels=[h.get_label() for h in handles], loc="upper left", bbox_to_anchor=(right + 0.01, top),
               fontsize=8, title=title, title_fontsize=8, frameon=True, borderaxespad=0)


def main(path):
    out = os.path.dirname(os.path.abspath(path))
    with open(path) as f:
        doc = json.load(f)
    results = [r for r in doc["results"] if "refused" not in r]
    refused = [r for r in doc["results"] if "refused" in r]
    backends = [b["name"] for b in doc["backends"] if b.get("available")]
    devices = {b["name"]: b.get("device", {}) for b in doc["backends"]}

    def device_label(backend):
        dev = devices.get(backend, {})
        soft = " (software rasterizer)" if dev.get("softwareRasterizer") else ""
        return f"{backend}: {dev.get('deviceName', '?')}{soft}"

    def short(r):
        return r["key"].split("/", 1)[1].rsplit("/", 1)[0]

    def options(r):
        """short(r) without the technique: the case's options ("msaa4", "scale2", ...)."""
        tokens = short(r).split("/")
        return tokens[1:] if tokens and tokens[0] == r["settings"]["technique"] else tokens

    def frame_ms(r):
        return r["cpuFrameMs"]["median"]

    def error(r):
        return r["error"]["percentOver5"]

    os.makedirs(os.path.join(out, "charts"), exist_ok=True)
    charts = []

    def save(fig, name, caption, rows):
        for ext in ("png", "svg"):
            fig.savefig(os.path.join(out, "charts", f"{name}.{ext}"), dpi=90, bbox_inches="tight")
        plt.close(fig)
        charts.append((name, caption, weight(rows)))

    def per_backend(title):
        fig, axes = plt.subplots(1, max(1, len(backends)), figsize=(6.5 * max(1, len(backends)), 5), squeeze=False)
        fig.suptitle(title)
        return fig, list(zip(axes[0], backends))

    def titled(ax, b, xlabel, ylabel, heading=None, empty=False):
        if empty:  # nothing measured on this backend (refused: the report's "Refused" list)
            ax.text(0.5, 0.5, "no measurements", transform=ax.transAxes, ha="center", va="center", color="0.4")
        ax.set_xlabel(xlabel)
        ax.set_ylabel(ylabel)
        ax.set_title((heading + "\n" if heading else "") + device_label(b), fontsize=9)
        ax.grid(alpha=0.3)
        ax.grid(alpha=0.12, which="minor")

    # 1. Speed against accuracy, per scene configuration: every technique and option a point (the
    # technique's colour and marker; its options, the marker's fill), the Pareto front (nothing both
    # faster and more exact) dashed.
    groups = {}
    for r in results:
        s = r["settings"]
        if s["iblSamples"] or s["lights"]:
            continue  # charted below
        groups.setdefault((s["scene"], s["shadows"]["enabled"], s["iblPrefiltered"]), []).append(r)
    for (scene, shadows, prefiltered), rows in sorted(groups.items()):
        label = scene + (" with shadows" if shadows else "") + (" and prefiltered IBL" if prefiltered else "")
        # The options every case of the chart shares are said once, in the legend's title.
        common = set(options(rows[0])).intersection(*(options(r) for r in rows))
        variant = {id(r): "/".join(o for o in options(r) if o not in common) for r in rows}
        variants = list(dict.fromkeys(variant[id(r)] for r in rows))
        fill = {v: VARIANT_FILLS[i % len(VARIANT_FILLS)] for i, v in enumerate(variants)}
        size = {v: 7 + 3 * (i // len(VARIANT_FILLS)) for i, v in enumerate(variants)}
        fig, axes = per_backend(f"{label}: frame time against error (Pareto front dashed)")
        for ax, b in axes:
            pts = sorted((r for r in rows if r["backend"] == b), key=frame_ms)
            for r in pts:
                colour, marker, _ = technique_style(r["settings"]["technique"])
                v = variant[id(r)]
                ax.plot([frame_ms(r)], [error(r)], linestyle="none", marker=marker, color=colour, fillstyle=fill[v],
                        markersize=size[v], alpha=0.9)
            front, best = [], float("inf")
            for r in pts:
                if error(r) < best:
                    best = error(r)
                    front.append(r)
            if front:
                ax.plot([frame_ms(r) for r in front], [error(r) for r in front], "k--", linewidth=0.8, drawstyle="steps-post")
            scale_axis(ax, "x", [frame_ms(r) for r in pts])
            scale_axis(ax, "y", [error(r) for r in pts])
            titled(ax, b, "CPU frame time, median (ms)", "pixels beyond 5/255 of the exact image (%)", empty=not pts)
        handles = [technique_handle(t, line=False) for t in technique_order(r["settings"]["technique"] for r in rows)]
        if len(variants) > 1:
            handles.append(Line2D([], [], linestyle="none", label="options (marker fill):"))
            handles += [Line2D([], [], color="0.35", marker="o", linestyle="none", fillstyle=fill[v], markersize=size[v],
                               label=v or "(no options)") for v in variants]
        handles.append(Line2D([], [], color="k", linestyle="--", linewidth=0.8, label="Pareto front"))
        figure_legend(fig, [ax for ax, _ in axes], handles,
                      "technique" + (f" (all: {'/'.join(o for o in options(rows[0]) if o in common)})" if common else ""))
        save(fig, "time_vs_error_" + slug(label), f"{label}: speed against accuracy", rows)

    # 2. Scaling: frame time against light count. One row of plots (one per backend) per sweep: the
    # cases that differ only in technique and light count, one line per technique. Cases measured at
    # one light count only (MSAA or illumination-scale variants, a 720p comparison) are a row of
    # their own per scene, size and light count: each case's frame time, one line per case.
    # Rows in weight() order, heaviest first.
    lights = [r for r in results if r["settings"]["lights"]]
    if lights:
        configs = {}
        for r in lights:
            rest = {k: v for k, v in r["settings"].items() if k not in ("lights", "technique")}
            configs.setdefault(json.dumps(rest, sort_keys=True), []).append(r)
        rows, fixed = [], {}
        for rs in configs.values():
            if len({r["settings"]["lights"] for r in rs}) > 1:
                rows.append(("sweep", rs))
            else:
                s = rs[0]["settings"]
                fixed.setdefault((s["scene"], s["width"], s["height"], s["lights"]), []).extend(rs)
        rows += [("fixed", rs) for rs in fixed.values()]
        rows.sort(key=lambda row: -weight(row[1]))
        cats = {id(rs): list(dict.fromkeys(short(r) for r in rs)) for kind, rs in rows if kind == "fixed"}
        heights = [4.5 if kind == "sweep" else max(2.2, 0.3 * len(cats[id(rs)]) + 1.4) for kind, rs in rows]
        ncols = max(1, len(backends))
        total = sum(heights) + 0.9 * len(rows) + 0.95
        fig = plt.figure(figsize=(6.5 * ncols, total))
        grid = fig.add_gridspec(len(rows), ncols, height_ratios=heights, top=1 - 0.95 / total, bottom=0.5 / total,
                                hspace=0.9 * len(rows) / sum(heights), wspace=0.22)
        scenes = ", ".join(dict.fromkeys(r["settings"]["scene"] for r in lights))
        fig.suptitle(f"{scenes}: frame time against the number of lights")
        all_axes, drawn = [], set()
        for i, (kind, rs) in enumerate(rows):
            s = rs[0]["settings"]
            heading = f"{s['scene']} at {s['width']}x{s['height']}"
            first = None
            for j, b in enumerate(backends):
                ax = fig.add_subplot(grid[i, j], sharey=first if kind == "fixed" else None)
                first = ax if first is None else first
                all_axes.append(ax)
                mine = [r for r in rs if r["backend"] == b]
                if kind == "sweep":
                    opts = "/".join(options(rs[0]))
                    for t in technique_order(r["settings"]["technique"] for r in mine):
                        pts = sorted((r for r in mine if r["settings"]["technique"] == t), key=lambda r: r["settings"]["lights"])
                        colour, marker, style = technique_style(t)
                        ax.plot([r["settings"]["lights"] for r in pts], [frame_ms(r) for r in pts], color=colour, marker=marker,
                                linestyle=style, markersize=6)
                        drawn.add(t)
                    scale_axis(ax, "x", [r["settings"]["lights"] for r in rs], count=True)
                    scale_axis(ax, "y", [frame_ms(r) for r in mine])
                    titled(ax, b, "point lights", "CPU frame time, median (ms)", heading + (f", {opts}" if opts else ""),
                           empty=not mine)
                else:
                    names = cats[id(rs)]
                    for r in mine:
                        colour, marker, _ = technique_style(r["settings"]["technique"])
                        ax.plot([frame_ms(r)], [names.index(short(r))], linestyle="none", color=colour, marker=marker,
                                markersize=7)
                        drawn.add(r["settings"]["technique"])
                    ax.set_yticks(range(len(names)))
                    ax.set_yticklabels(names, fontsize=8)
                    ax.set_ylim(len(names) - 0.5, -0.5)  # the first case at the top
                    scale_axis(ax, "x", [frame_ms(r) for r in mine])
                    titled(ax, b, "CPU frame time, median (ms)", "case" if j == 0 else "",
                           f"{heading}, {s['lights']} lights", empty=not mine)
                    if j:
                        ax.tick_params(labelleft=False)
        figure_legend(fig, all_axes, [technique_handle(t) for t in technique_order(drawn)], "technique")
        save(fig, "scaling_lights", "scaling with the light count", lights)

    # 3. Image-based lighting: error against the sample count; the fast path as a dashed level.
    ibl = [r for r in results if r["settings"]["iblSamples"] or r["settings"]["iblPrefiltered"]]
    if any(r["settings"]["iblSamples"] for r in ibl):
        fig, axes = per_backend("image-based lighting: error against samples per term (fast path dashed)")
        drawn = set()
        for ax, b in axes:
            for t in technique_order(r["settings"]["technique"] for r in ibl):
                rows = [r for r in ibl if r["backend"] == b and r["settings"]["technique"] == t]
                pts = sorted((r for r in rows if r["settings"]["iblSamples"]), key=lambda r: r["settings"]["iblSamples"])
                colour, marker, style = technique_style(t)
                if pts:
                    ax.plot([r["settings"]["iblSamples"] for r in pts], [error(r) for r in pts], color=colour, marker=marker,
                            linestyle=style, markersize=6)
                    drawn.add(t)
                for r in rows:
                    if r["settings"]["iblPrefiltered"]:
                        ax.axhline(error(r), color=colour, linestyle="--", linewidth=0.8)
                        drawn.add(t)
            mine = [r for r in ibl if r["backend"] == b]
            scale_axis(ax, "x", [r["settings"]["iblSamples"] for r in mine if r["settings"]["iblSamples"]], count=True)
            scale_axis(ax, "y", [error(r) for r in mine])
            titled(ax, b, "importance samples per term", "pixels beyond 5/255 of the converged integral (%)", empty=not mine)
        handles = [technique_handle(t) for t in technique_order(drawn)]
        if any(r["settings"]["iblPrefiltered"] for r in ibl):
            handles.append(Line2D([], [], color="0.35", linestyle="--", linewidth=0.8, label="prefiltered (fast path)"))
        figure_legend(fig, [ax for ax, _ in axes], handles, "technique")
        save(fig, "ibl_convergence", "image-based lighting convergence", ibl)

    # 4. Memory per technique: transient bytes per pixel with and without aliasing.
    # The first scene configuration of the sweep (builtin:spheres in the quick sweep), one sample, full rate.
    first = groups.get(("builtin:spheres", False, False)) or next(iter(groups.values()), [])
    mem = [r for r in first if r["settings"]["illumScale"] == 1 and r["settings"]["msaa"] == 1]
    if mem:
        fig, axes = per_backend(f"transient memory per technique ({mem[0]['settings']['scene']}, one sample, full rate)")
        for ax, b in axes:
            rows = [r for r in mem if r["backend"] == b]
            names = [short(r) for r in rows]
            x = range(len(rows))
            ax.bar([i - 0.2 for i in x], [r["memory"]["bytesPerPixelWithoutAliasing"] for r in rows], 0.4, color="#1f77b4")
            ax.bar([i + 0.2 for i in x], [r["memory"]["bytesPerPixelWithAliasing"] for r in rows], 0.4, color="#ff7f0e")
            ax.set_xticks(list(x))
            ax.set_xticklabels(names, rotation=45, ha="right", fontsize=7)
            scale_axis(ax, "y", [r["memory"][k] for r in rows
                                 for k in ("bytesPerPixelWithoutAliasing", "bytesPerPixelWithAliasing")])
            titled(ax, b, "", "transient bytes per pixel", empty=not rows)
        figure_legend(fig, [ax for ax, _ in axes],
                      [Line2D([], [], color="#1f77b4", marker="s", linestyle="none", markersize=9, label="without aliasing"),
                       Line2D([], [], color="#ff7f0e", marker="s", linestyle="none", markersize=9, label="with aliasing")],
                      "transient memory")
        save(fig, "memory", "transient memory per technique", mem)

    # The report.
    e = html.escape
    engine = doc.get("engine", {})
    parts = [f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>fe bench report</title>
<style>body{{font-family:sans-serif;margin:1em}} table{{border-collapse:collapse}} td,th{{border:1px solid #ccc;padding:3px;
font-size:12px;vertical-align:top}} img.t{{image-rendering:pixelated;width:144px}} .chart{{max-width:100%}}</style>
<script>window.feErrors = 0; window.addEventListener('error', () => window.feErrors++, true);
const feConsoleError = console.error; console.error = (...a) => {{ window.feErrors++; feConsoleError(...a); }};</script>
</head><body>
<h1>fe bench</h1>
<p>{e(engine.get('name', ''))} {e(engine.get('version', ''))} ({e(engine.get('commit', ''))}), {e(doc.get('date', ''))};
{len(results)} measurements, {len(refused)} refused. Error: against the CPU double-precision reference of the same
scene and camera, on the displayed 8-bit image.</p>
<ul>{''.join(f'<li>{e(device_label(b))}</li>' for b in backends)}</ul>
<h2>Charts</h2>"""]
    # The charts heaviest first (weight(): the many-light sweeps open the page, the quick sweep's tiny
    # cases close it); charts of equal weight in the order drawn.
    for name, caption, _ in sorted(charts, key=lambda c: -c[2]):
        parts.append(f'<figure><img class="chart" src="charts/{name}.png" alt="{e(caption)}"><figcaption>{e(caption)} '
                     f'(<a href="charts/{name}.svg">SVG</a>)</figcaption></figure>')
    parts.append("<h2>Images</h2><p>Per case: the reference, then per backend the image, its FLIP heat map (black: "
                 "no visible difference, white: the largest) and its metrics.</p><table><tr><th>case</th><th>reference</th>")
    parts += [f"<th>{e(device_label(b))}</th>" for b in backends]
    parts.append("</tr>")
    keys = list(dict.fromkeys(r["key"] for r in results))  # the sweep's order (summary.md's)
    # The page's image rows in the charts' order: heaviest case first (weight()), else the sweep's order.
    for k in sorted(keys, key=lambda k: -weight([r for r in results if r["key"] == k])):
        rows = {r["backend"]: r for r in results if r["key"] == k}
        first = next(iter(rows.values()))
        ref = first.get("referenceImage")
        parts.append(f"<tr><td>{e(k)}<br>{e(first.get('reference', ''))}</td><td>"
                     + (f'<img class="t" src="images/{e(ref)}" alt="reference">' if ref else "") + "</td>")
        for b in backends:
            r = rows.get(b)
            if not r:
                parts.append("<td>refused</td>")
                continue
            m = r["error"]
            psnr = "inf" if m["psnr"] is None else f"{m['psnr']:.1f}"
            imgs = ""
            if "image" in r:
                imgs = (f'<img class="t" src="images/{e(r["image"])}" alt="image"> '
                        f'<img class="t" src="images/{e(r["flipImage"])}" alt="FLIP">')
            parts.append(f"<td>{imgs}<br>{r['cpuFrameMs']['median']:.1f} ms; PSNR {psnr} dB, SSIM {m['ssim']:.4f}, "
                         f"FLIP {m['flip']:.4f}, {m['percentOver5']:.2f} % over 5/255, max {m['maxAbs']:.3f}</td>")
        parts.append("</tr>")
    parts.append("</table>")
    stability = doc.get("stability", [])
    techniques = list(dict.fromkeys(r["technique"] for r in stability))

    def outcome(r):
        if "refused" in r:
            return "refused: " + r["refused"]
        if "nonFinite" in r:
            return f"NON-FINITE ({r['nonFinite']})"
        if "percentOver5" in r:
            return f"{r['percentOver5']:.2f} %"
        return "finite"

    # The size most cases rendered at; a case at another size is labelled with it.
    sizes = [(r["width"], r["height"]) for r in stability if "width" in r]
    suite_size = max(set(sizes), key=sizes.count) if sizes else None

    def stability_table():
        """Per case: its bound and, per technique, None or (the first backend's outcome, the other
        backends whose outcome differs, as "backend: outcome")."""
        for case in dict.fromkeys(r["case"] for r in stability):
            rows = [r for r in stability if r["case"] == case]
            cells = []
            for t in techniques:
                mine = [r for r in rows if r["technique"] == t]
                first = outcome(mine[0]) if mine else None
                cells.append(None if not mine else
                             (first, [f"{r['backend']}: {outcome(r)}" for r in mine[1:] if outcome(r) != first]))
            # A case rendered at its own size (the heaviest light counts) says so.
            size = f" at {rows[0]['width']}x{rows[0]['height']}" if "width" in rows[0] and (
                rows[0]["width"], rows[0]["height"]) != suite_size else ""
            yield case + size, rows[0]["bound"], cells

    if stability:
        parts.append("<h2>Stability</h2><p>Per case and technique: the percentage of pixels beyond 5/255 of the CPU "
                     "reference (bound for the exact techniques in brackets), or the refusal and its reason. Backends "
                     "that differ from the first are named.</p><table><tr><th>case</th>")
        parts += [f"<th>{e(t)}</th>" for t in techniques]
        parts.append("</tr>")

        for case, bound, cells in stability_table():
            parts.append(f"<tr><td>{e(case)}" + (f" [{bound:g} %]" if bound >= 0 else "") + "</td>")
            for cell in cells:
                parts.append("<td></td>" if cell is None else
                             f"<td>{e(cell[0])}" + "".join(f"<br>{e(o)}" for o in cell[1]) + "</td>")
            parts.append("</tr>")
        parts.append("</table>")
    conformance = doc.get("conformance")
    if conformance:
        summary = conformance.get("summary", {})
        parts.append(f"<h2>Conformance</h2><p>{summary.get('passed', 0)} checks passed, {summary.get('failed', 0)} failed. "
                     "Each backend's images against the first backend's: the two images and their difference (pixels "
                     "beyond the tolerance), with the tolerance and its reason.</p><table><tr><th>comparison</th>"
                     "<th>first backend</th><th>other backend</th><th>difference</th><th>result</th></tr>")
        q = urllib.parse.quote
        for c in conformance.get("comparisons", []):
            ref = f"conformance/{q(c['reference'])}/{q(c['case'] + '_' + c['image'])}.png"
            other = f"conformance/{q(c['backend'])}/{q(c['case'] + '_' + c['image'])}.png"
            diff = f"conformance/{q('diff_' + c['reference'] + '_' + c['backend'] + '_' + c['case'] + '_' + c['image'])}.png"
            m, t = c.get("metrics", {}), c.get("tolerance", {})
            parts.append(f"<tr><td>{e(c['name'])}</td><td><img class=\"t\" src=\"{ref}\" alt=\"first\"></td>"
                         f"<td><img class=\"t\" src=\"{other}\" alt=\"other\"></td><td><img class=\"t\" src=\"{diff}\" alt=\"difference\"></td>"
                         f"<td>{'pass' if c['passed'] else 'FAIL'}: {m.get('pixelsOverTolerance', 0)} pixels over "
                         f"{t.get('absolute', 0)}, max {m.get('maxAbsError', 0):.4f}; {e(str(t.get('reason', '')))}</td></tr>")
        parts.append("</table>")
    if refused:
        parts.append("<h2>Refused</h2><ul>" + "".join(f"<li>{e(r['backend'])} {e(r['key'])}: {e(r['refused'])}</li>" for r in refused)
                     + "</ul>")
    # For the browser test: how many images loaded, how many did not, and script errors.
    parts.append("""<script>
window.addEventListener('load', () => {
  const imgs = Array.from(document.images);
  const broken = imgs.filter(i => !i.complete || i.naturalWidth === 0).length;
  document.body.dataset.images = imgs.length;
  document.body.dataset.broken = broken;
  document.body.dataset.errors = window.feErrors;
});
</script></body></html>""")
    with open(os.path.join(out, "report.html"), "w") as f:
        f.write("\n".join(parts))

    # summary.md: the same figures as Markdown tables, for docs/BENCHMARKS.md (generated, not typed).
    md = [f"Generated by `fe {' '.join(doc.get('arguments', ['bench']))}` ({engine.get('version', '')}, "
          f"{engine.get('commit', '')}) on {doc.get('date', '')}"
          + (f" in {doc['elapsedSeconds']:.0f} s" if "elapsedSeconds" in doc else "") + "."
          + (f" {doc['description']}" if doc.get("description") else ""), ""]
    for b in backends:
        dev = devices.get(b, {})
        md.append(f"- {b}: {dev.get('deviceName', '?')}, {dev.get('apiVersion', '')}, {dev.get('driverInfo', '')}"
                  + (" (software rasterizer: times are CPU rasterization)" if dev.get("softwareRasterizer") else ""))
    md.append("")
    md.append("| case | " + " | ".join(f"{b} ms" for b in backends)
              + " | PSNR dB | SSIM | FLIP | % over 5/255 | lights/px mean, p95, max | reaching/px |")
    md.append("|---|" + "---|" * len(backends) + "---|---|---|---|---|---|")
    for k in keys:
        rows = {r["backend"]: r for r in results if r["key"] == k}
        first = next(iter(rows.values()))
        m = first["error"]
        psnr = "inf" if m["psnr"] is None else f"{m['psnr']:.1f}"
        times = " | ".join(f"{rows[b]['cpuFrameMs']['median']:.1f}" if b in rows else "refused" for b in backends)
        lights = first.get("lightsEvaluated", {})
        evaluated = (f"{lights['mean']:.1f}, {lights['p95']}, {lights['max']} ({lights['lists']})" if lights.get("measured")
                     else lights.get("lists", ""))
        reaching = f"{lights['reaching']:.1f}" if "reaching" in lights else ""
        if lights.get("pixelsMissingALight"):
            reaching += f" ({lights['pixelsMissingALight']} px MISS a light)"
        md.append(f"| {k} | {times} | {psnr} | {m['ssim']:.4f} | {m['flip']:.4f} | {m['percentOver5']:.2f} | {evaluated} "
                  f"| {reaching} |")
    md.append("")
    md.append(f"Error columns: {backends[0] if backends else ''}'s image (the backends agree, see the report). "
              "Times: median CPU frame over the timed frames. Lights/px: the lights the shading loop walked "
              "per pixel of a surface; reaching/px: the lights whose range reaches that surface, the least any exact "
              "culling walks.")
    # Each pass's GPU time (median ms) and the transient memory, per backend and case.
    md += ["", "GPU time per render-graph pass (median ms; the last column is the CPU frame) and the transient "
           "memory in bytes per pixel, with / without aliasing. The method column says how the pass times were "
           "measured: the GPU's timestamps where they sum to at least half the frame, else a flush-and-wait "
           "profiling run (each pass submitted and waited for alone; on lavapipe a pass's timestamps measure "
           "command processing, not rasterisation), with the timestamps' share of the frame:", "",
           "| backend | case | passes (GPU ms) | method | CPU frame ms | transient B/px |", "|---|---|---|---|---|---|"]
    for b in backends:
        for k in keys:
            r = next((r for r in results if r["key"] == k and r["backend"] == b), None)
            if r is None:
                continue
            passes = ", ".join(f"{name} {v['median']:.1f}" for name, v in r.get("gpuPassMs", {}).items())
            mem = r.get("memory", {})
            method = r.get("passTimeMethod", "gpu-timestamps")
            if "timestampShareOfFrame" in r:
                method += f" ({100 * r['timestampShareOfFrame']:.0f} %)"
            md.append(f"| {b} | {k} | {passes} | {method} | {r['cpuFrameMs']['median']:.1f} | "
                      f"{mem.get('bytesPerPixelWithAliasing', 0):.1f} / {mem.get('bytesPerPixelWithoutAliasing', 0):.1f} |")
    for r in refused:
        md.append(f"| {r['backend']} | {r['key']} | refused: {r['refused']} | | | |")
    if stability:
        md += ["", "The stability suite: per case and technique, the percentage of pixels beyond 5/255 of the CPU "
               "reference (the exact techniques' bound in brackets), \"refused\" (the renderer refused the scene with "
               "its reason) or \"finite\" (no exact image; every pixel finite). Backends that differ from the first "
               "are named in the cell.", "",
               "| case | " + " | ".join(techniques) + " |", "|---|" + "---|" * len(techniques)]
        for case, bound, cells in stability_table():
            # The refusal's reason is listed once below the table, not in every cell.
            text = ["" if c is None else "; ".join(["refused" if c[0].startswith("refused") else c[0]] + c[1]) for c in cells]
            md.append(f"| {case}" + (f" [{bound:g} %]" if bound >= 0 else "") + " | " + " | ".join(text) + " |")
        reasons = sorted({r["refused"] for r in stability if "refused" in r})
        if reasons:
            md += ["", "Refusals, as printed:"] + [f"- {x}" for x in reasons]
    with open(os.path.join(out, "summary.md"), "w") as f:
        f.write("\n".join(md) + "\n")
    print(f"wrote {len(charts)} charts, {os.path.join(out, 'report.html')} and {os.path.join(out, 'summary.md')}")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: report.py DIR/results.json")
    main(sys.argv[1])
