#!/usr/bin/env python3
"""fe bench's charts and report (called by `fe bench`, or by hand: report.py DIR/results.json).

Reads results.json and writes beside it charts/*.png and charts/*.svg (Debian's
python3-matplotlib) and report.html: the charts, then per case a row of every backend's image,
FLIP heat map against the exact reference and metrics. Every chart names its axes, units and
devices, and says when a device is a software rasterizer.
"""
import html
import json
import os
import sys
import urllib.parse

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def slug(text):
    return "".join(c if c.isalnum() or c == "-" else "_" for c in text).strip("_")


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

    os.makedirs(os.path.join(out, "charts"), exist_ok=True)
    charts = []

    def save(fig, name, caption):
        for ext in ("png", "svg"):
            fig.savefig(os.path.join(out, "charts", f"{name}.{ext}"), dpi=90, bbox_inches="tight")
        plt.close(fig)
        charts.append((name, caption))

    def log2_axes(ax, backend, xlabel, ylabel):
        ax.set_xscale("log", base=2)
        ax.set_xlabel(xlabel)
        ax.set_ylabel(ylabel)
        ax.set_title(device_label(backend), fontsize=9)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)

    def per_backend(title):
        fig, axes = plt.subplots(1, max(1, len(backends)), figsize=(6.5 * max(1, len(backends)), 5), squeeze=False)
        fig.suptitle(title)
        return fig, list(zip(axes[0], backends))

    # 1. Speed against accuracy, per scene configuration: every technique and option a point,
    # the Pareto front (nothing both faster and more exact) dashed.
    groups = {}
    for r in results:
        s = r["settings"]
        if s["iblSamples"] or s["lights"]:
            continue  # charted below
        groups.setdefault((s["scene"], s["shadows"]["enabled"], s["iblPrefiltered"]), []).append(r)
    for (scene, shadows, prefiltered), rows in sorted(groups.items()):
        label = scene + (" with shadows" if shadows else "") + (" and prefiltered IBL" if prefiltered else "")
        fig, axes = per_backend(f"{label}: frame time against error (Pareto front dashed)")
        for ax, b in axes:
            pts = sorted((r for r in rows if r["backend"] == b), key=lambda r: r["cpuFrameMs"]["median"])
            for r in pts:
                ax.scatter(r["cpuFrameMs"]["median"], r["error"]["percentOver5"], s=18)
                ax.annotate(short(r), (r["cpuFrameMs"]["median"], r["error"]["percentOver5"]), fontsize=6,
                            xytext=(3, 2), textcoords="offset points")
            front, best = [], float("inf")
            for r in pts:
                if r["error"]["percentOver5"] < best:
                    best = r["error"]["percentOver5"]
                    front.append(r)
            if front:
                ax.plot([r["cpuFrameMs"]["median"] for r in front], [r["error"]["percentOver5"] for r in front], "k--",
                        linewidth=0.8, drawstyle="steps-post")
            ax.set_xlabel("CPU frame time, median (ms)")
            ax.set_ylabel("pixels beyond 5/255 of the exact image (%)")
            ax.set_title(device_label(b), fontsize=9)
            ax.grid(alpha=0.3)
        save(fig, "time_vs_error_" + slug(label), f"{label}: speed against accuracy")

    # 2. Scaling: frame time against light count.
    lights = [r for r in results if r["settings"]["lights"]]
    if lights:
        fig, axes = per_backend("builtin:lights: frame time against the number of lights")
        for ax, b in axes:
            for t in sorted({r["settings"]["technique"] for r in lights}):
                pts = sorted((r for r in lights if r["backend"] == b and r["settings"]["technique"] == t),
                             key=lambda r: r["settings"]["lights"])
                ax.plot([r["settings"]["lights"] for r in pts], [r["cpuFrameMs"]["median"] for r in pts], "o-", label=t)
            log2_axes(ax, b, "point lights", "CPU frame time, median (ms)")
        save(fig, "scaling_lights", "scaling with the light count")

    # 3. Image-based lighting: error against the sample count; the fast path as a dashed level.
    ibl = [r for r in results if r["settings"]["iblSamples"] or r["settings"]["iblPrefiltered"]]
    if any(r["settings"]["iblSamples"] for r in ibl):
        fig, axes = per_backend("image-based lighting: error against samples per term (fast path dashed)")
        for ax, b in axes:
            for t in sorted({r["settings"]["technique"] for r in ibl}):
                rows = [r for r in ibl if r["backend"] == b and r["settings"]["technique"] == t]
                pts = sorted((r for r in rows if r["settings"]["iblSamples"]), key=lambda r: r["settings"]["iblSamples"])
                line, = ax.plot([r["settings"]["iblSamples"] for r in pts], [r["error"]["percentOver5"] for r in pts], "o-",
                                label=t)
                for r in rows:
                    if r["settings"]["iblPrefiltered"]:
                        ax.axhline(r["error"]["percentOver5"], color=line.get_color(), linestyle="--", linewidth=0.8)
            log2_axes(ax, b, "importance samples per term", "pixels beyond 5/255 of the converged integral (%)")
        save(fig, "ibl_convergence", "image-based lighting convergence")

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
            ax.bar([i - 0.2 for i in x], [r["memory"]["bytesPerPixelWithoutAliasing"] for r in rows], 0.4, label="without aliasing")
            ax.bar([i + 0.2 for i in x], [r["memory"]["bytesPerPixelWithAliasing"] for r in rows], 0.4, label="with aliasing")
            ax.set_xticks(list(x))
            ax.set_xticklabels(names, rotation=45, ha="right", fontsize=7)
            ax.set_ylabel("transient bytes per pixel")
            ax.set_title(device_label(b), fontsize=9)
            ax.legend(fontsize=7)
        save(fig, "memory", "transient memory per technique")

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
    for name, caption in charts:
        parts.append(f'<figure><img class="chart" src="charts/{name}.png" alt="{e(caption)}"><figcaption>{e(caption)} '
                     f'(<a href="charts/{name}.svg">SVG</a>)</figcaption></figure>')
    parts.append("<h2>Images</h2><p>Per case: the reference, then per backend the image, its FLIP heat map (black: "
                 "no visible difference, white: the largest) and its metrics.</p><table><tr><th>case</th><th>reference</th>")
    parts += [f"<th>{e(device_label(b))}</th>" for b in backends]
    parts.append("</tr>")
    keys = list(dict.fromkeys(r["key"] for r in results))
    for k in keys:
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
            yield case, rows[0]["bound"], cells

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
              + " | PSNR dB | SSIM | FLIP | % over 5/255 | lights/px mean, p95, max |")
    md.append("|---|" + "---|" * len(backends) + "---|---|---|---|---|")
    for k in keys:
        rows = {r["backend"]: r for r in results if r["key"] == k}
        first = next(iter(rows.values()))
        m = first["error"]
        psnr = "inf" if m["psnr"] is None else f"{m['psnr']:.1f}"
        times = " | ".join(f"{rows[b]['cpuFrameMs']['median']:.1f}" if b in rows else "refused" for b in backends)
        lights = first.get("lightsEvaluated", {})
        evaluated = (f"{lights['mean']:.1f}, {lights['p95']}, {lights['max']} ({lights['lists']})" if lights.get("measured")
                     else lights.get("lists", ""))
        md.append(f"| {k} | {times} | {psnr} | {m['ssim']:.4f} | {m['flip']:.4f} | {m['percentOver5']:.2f} | {evaluated} |")
    md.append("")
    md.append(f"Error columns: {backends[0] if backends else ''}'s image (the backends agree, see the report). "
              "Times: median CPU frame over the timed frames. Lights/px: the lights the shading loop walked per pixel "
              "(of a surface, for lists; every light: at every pixel).")
    # Each pass's GPU time (median ms) and the transient memory, per backend and case.
    md += ["", "GPU time per render-graph pass (median ms; the last column is the CPU frame) and the transient "
           "memory in bytes per pixel, with / without aliasing:", "",
           "| backend | case | passes (GPU ms) | CPU frame ms | transient B/px |", "|---|---|---|---|---|"]
    for b in backends:
        for k in keys:
            r = next((r for r in results if r["key"] == k and r["backend"] == b), None)
            if r is None:
                continue
            passes = ", ".join(f"{name} {v['median']:.1f}" for name, v in r.get("gpuPassMs", {}).items())
            mem = r.get("memory", {})
            md.append(f"| {b} | {k} | {passes} | {r['cpuFrameMs']['median']:.1f} | "
                      f"{mem.get('bytesPerPixelWithAliasing', 0):.1f} / {mem.get('bytesPerPixelWithoutAliasing', 0):.1f} |")
    for r in refused:
        md.append(f"| {r['backend']} | {r['key']} | refused: {r['refused']} | | |")
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
