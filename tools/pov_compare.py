#!/usr/bin/python3
"""Renders the same pictures with softtrace and POV-Ray 3.7 and compares silhouettes and times.

Cases: `blobN` (tools/blob_scene.py: N murakami spheres blended at iso 0.5, POV's `blob` of the
same spheres with strength 1 and threshold 0.5), `meetsK` (1000 such spheres of the radius at which
a ray through their cube passes through K supports on average: blob_scene.py --meets K), `fig12b` (scenes/fig000_12b_soft_blend.json, POV's
`isosurface` of the same blend), and POV-Ray scenes converted by tools/pov2softtrace.py:
`pov:NAME` (tools/pov_cases/NAME.pov or POV-Ray's sample objects/NAME.pov) and `cloudN` (N mixed
sphere and cylinder components, tools/pov_cloud.py); `real` names the whole real-world-like set;
`segtrace` is the Segment Tracing paper's 1001 `cubic` blobs (tools/segment_tracing_scene.py),
exact in softtrace, against POV-Ray's blob of the closest `murakami` fit: not the same surface, so
its IoU is reported but not held to 0.999. Both renderers get the same size, 1 sample per pixel and the same
number of threads. Rounds are interleaved (every case once, then again) so that a load spike on a
shared machine hits every case alike; the medians over --repeat rounds are reported. Every timed
process starts after the same idle pause (--settle), and the two renderers take turns at going
first: on a virtual machine a process that starts right after a burst of CPU work (POV-Ray's trace,
or a busy loop) runs several milliseconds slower than one after an idle second (docs/performance.md
measures it), so without the pause whichever renderer ran second would pay for the first.

Per case it prints the silhouettes' IoU (alpha >= 0.5 in softtrace's PNG and POV's +UA PNG), the
colours' mean difference (the largest of premultiplied linear R, G, B per pixel, in 1/255), each
renderer's frame time (softtrace bench's wall time; POV's "Trace Time" statistic), each whole
process's wall time, the ratios, and softtrace's evaluations per primary ray that enters a box.
For fig12b it also renders POV at max_gradient 0.74 (a bound on |grad f| over the whole box:
|P'| <= 2 times |grad d_bar| <= 0.22 plus |grad d_cube| <= 0.15) and counts the pixels whose
coverage differs from the timed render: 0 means the timed max_gradient leaves no holes there.

With --plot it draws the blob cases' time per primary ray against N, both renderers, with gnuplot.

Uses Debian's python3 and installs povray, povray-includes (colors.inc), povray-examples (the
blob*.pov samples), python3-pil and gnuplot-nox when missing.

usage: tools/pov_compare.py [--cases blob10,blob100,blob1000,blob10000,fig12b|real|pov:NAME,cloudN,
                                   meetsK,segtrace]
           [--width 160] [--height 120] [--threads 2] [--repeat 3] [--max-gradient 0.4]
           [--settle 1.0] [--build build] [--work DIR] [--json results.json] [--plot time_per_ray.png]
"""
import argparse
import json
import os
import re
import statistics
import subprocess
import sys
import time

TOOLS = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(TOOLS)
sys.path.insert(0, TOOLS)
import blob_scene  # noqa: E402
import pov2softtrace  # noqa: E402
import pov_cloud  # noqa: E402
import pov_scene  # noqa: E402
import segment_tracing_scene  # noqa: E402
from povsdl.lexer import PovError  # noqa: E402
from povsdl.scene import convert, obj_text  # noqa: E402

PACKAGES = ["povray", "povray-includes", "povray-examples", "python3-pil", "gnuplot-nox"]
SAFE_MAX_GRADIENT = 0.74
POV_SAMPLES = "/usr/share/povray-3.7/scenes/objects"
# The real-world-like set: tools/pov_cases/, POV-Ray's own blob samples, and generated clouds of
# mixed components (tools/pov_cloud.py), each converted by tools/pov2softtrace.py.
REAL_WORLD = ("pov:molecule,pov:candle,pov:sheared,pov:chain,pov:golfball,pov:old_syntax,"
              "pov:blob,pov:blob1a,pov:blob1b,pov:blob1c,cloud300,cloud3000")


def install_missing():
    missing = [p for p in PACKAGES if subprocess.run(
        ["dpkg-query", "-W", "-f=${Status}", p], capture_output=True,
        text=True).stdout.find("install ok installed") < 0]
    if not missing:
        return
    sudo = [] if os.geteuid() == 0 else ["sudo"]
    print("installing:", " ".join(missing), file=sys.stderr)
    env = dict(os.environ, DEBIAN_FRONTEND="noninteractive")
    subprocess.run(sudo + ["apt-get", "update", "-qq"], check=True, env=env)
    subprocess.run(sudo + ["apt-get", "install", "-y", "-qq", "--no-install-recommends"] + missing,
                   check=True, env=env, stdout=subprocess.DEVNULL)


def check_pil():
    """Fails before any rendering if this interpreter cannot read the PNGs (python3-pil is
    Debian's, for /usr/bin/python3: another python3 first on PATH does not see it)."""
    try:
        import PIL  # noqa: F401
    except ImportError:
        sys.exit("pov_compare: %s cannot import PIL (Debian's python3-pil); run the script "
                 "itself (tools/pov_compare.py) or with /usr/bin/python3" % sys.executable)


def timed(cmd, settle):
    """Runs cmd after `settle` idle seconds; returns (wall seconds, user+system CPU seconds,
    stdout+stderr text)."""
    time.sleep(settle)
    t0 = time.perf_counter()
    p = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
    out = p.stdout.read()
    _, status, usage = os.wait4(p.pid, 0)
    wall = time.perf_counter() - t0
    p.returncode = os.waitstatus_to_exitcode(status)
    text = out.decode(errors="replace")
    if p.returncode != 0:
        sys.exit("pov_compare: %s failed (%d):\n%s" % (cmd[0], p.returncode, text[-2000:]))
    return wall, usage.ru_utime + usage.ru_stime, text


def read_json_scene(path):
    """A scene file as JSON (softtrace's scene files may have // comment lines)."""
    with open(path) as f:
        return json.loads("".join(l for l in f if not l.lstrip().startswith("//")))


def write_case(case, a, work):
    """Writes work/CASE.json and work/CASE.pov (and the hole check's .pov for fig12b)."""
    base = os.path.join(work, case)
    if case.startswith("blob"):
        sc = blob_scene.scene(int(case[4:]), 1, a.width, a.height)
        pov = pov_scene.header(sc, a.width, a.height) + pov_scene.blob(sc)
    elif case.startswith("meets"):
        sc = blob_scene.scene(1000, 1, a.width, a.height,
                              blob_scene.meets_radius(1000, float(case[5:])))
        pov = pov_scene.header(sc, a.width, a.height) + pov_scene.blob(sc)
    elif case == "fig12b":
        sc = read_json_scene(os.path.join(ROOT, "scenes", "fig000_12b_soft_blend.json"))
        head = pov_scene.header(sc, a.width, a.height)
        pov = head + pov_scene.isosurface_fig12b(sc, a.max_gradient, a.accuracy)
        with open(base + "_safe.pov", "w") as f:
            f.write(head + pov_scene.isosurface_fig12b(sc, SAFE_MAX_GRADIENT, a.accuracy))
    elif case == "segtrace":
        sc = segment_tracing_scene.scene(1, a.width, a.height)
        pov = pov_scene.header(sc, a.width, a.height) + segment_tracing_scene.pov_blob(sc)
    elif case.startswith("pov:") or case.startswith("cloud"):
        if case.startswith("cloud"):
            text = pov_cloud.scene(int(case[5:]), seed=1)
            source = base + "_source.pov"
            with open(source, "w") as f:
                f.write(text)
        else:
            source = pov_case_path(case[4:])
            with open(source) as f:
                text = f.read()
        meshes = []
        try:
            sc = convert(source, text, a.width, a.height, meshes)
        except PovError as e:
            sys.exit("%s:%d:%d: %s" % (source, e.line, e.col, e.message))
        for obj in pov2softtrace.mesh_objects(sc["objects"]):  # OBJ files beside the scene
            name = "%s_%s.obj" % (os.path.basename(base), obj["name"])
            with open(os.path.join(work, name), "w") as f:
                f.write(obj_text(meshes[obj["mesh"]]))
            obj["mesh"] = name
        # POV-Ray's alpha (+UA) is the coverage only where the background is transparent.
        pov = text + "\nbackground { rgbt <0, 0, 0, 1> }\n"
    else:
        sys.exit("pov_compare: unknown case '%s' (blobN, meetsK, fig12b, cloudN, pov:NAME or "
                 "segtrace)" % case)
    sc["image"] = {"width": a.width, "height": a.height, "spp": 1}
    with open(base + ".json", "w") as f:
        json.dump(sc, f)
    with open(base + ".pov", "w") as f:
        f.write(pov)
    return base


def pov_case_path(name):
    """tools/pov_cases/NAME.pov, POV-Ray's sample scenes/objects/NAME.pov, or a path."""
    for path in (os.path.join(TOOLS, "pov_cases", name + ".pov"),
                 os.path.join(POV_SAMPLES, name + ".pov"), name):
        if os.path.isfile(path):
            return path
    sys.exit("pov_compare: no POV-Ray scene '%s' in tools/pov_cases/ or %s" % (name, POV_SAMPLES))


def povray(a, pov, png):
    wall, cpu, text = timed(["povray", "+I" + pov, "+O" + png, "+W%d" % a.width,
                             "+H%d" % a.height, "+UA", "+WT%d" % a.threads, "-D", "-A",
                             "+FN8", "-V", "+GS"], a.settle)
    m = re.search(r"Trace Time:.*\(([\d.]+) seconds\)", text)
    if not m:
        sys.exit("pov_compare: no Trace Time in POV-Ray's statistics:\n" + text[-2000:])
    holes = re.search(r"maximum gradient found was ([\d.]+)", text)
    return {"trace_s": float(m.group(1)), "process_s": wall, "process_cpu_s": cpu,
            "gradient_found": float(holes.group(1)) if holes else None}


def softtrace(a, scene, png):
    exe = os.path.join(a.build, "softtrace")
    common = ["--width", str(a.width), "--height", str(a.height), "--threads", str(a.threads)]
    wall, cpu, _ = timed([exe, "render", scene, "-o", png, "--png-alpha", "--spp", "1",
                          "--quiet"] + common, a.settle)
    _, _, text = timed([exe, "bench", scene, "--repeat", "1", "--json", "--quiet"] + common, 0)
    bench = json.loads(text)
    return {"frame_s": bench["best_s"], "process_s": wall, "process_cpu_s": cpu,
            "primary": bench["primary"], "shadow": bench["shadow"], "commit": bench["commit"]}


def coverage(png):
    from PIL import Image  # installed by install_missing
    im = Image.open(png).convert("RGBA")
    return [px >= 128 for px in im.getchannel("A").getdata()]


def mean_difference(png1, png2):
    """The mean over the pixels of the largest difference of premultiplied linear RGB, in units
    of 1/255 (both backgrounds transparent black): how far the colours agree, where the IoU says
    only whether the silhouettes do."""
    from PIL import Image  # installed by install_missing

    def linear(c):
        c /= 255
        return c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4

    def pixels(png):
        return [[linear(px[i]) * px[3] / 255 for i in range(3)]
                for px in Image.open(png).convert("RGBA").getdata()]

    a, b = pixels(png1), pixels(png2)
    return 255 * sum(max(abs(p - q) for p, q in zip(x, y)) for x, y in zip(a, b)) / len(a)


def iou(m1, m2):
    both = sum(1 for x, y in zip(m1, m2) if x and y)
    either = sum(1 for x, y in zip(m1, m2) if x or y)
    return both / either if either else 1.0


def plot(results, png):
    """Time per primary ray against the number of blobs, log-log, softtrace and POV-Ray."""
    blobs = sorted((int(r["case"][4:]), r) for r in results if r["case"].startswith("blob"))
    if not blobs:
        return
    data = "\n".join("%d %g %g" % (n, r["st_us_per_ray"], r["pov_us_per_ray"]) for n, r in blobs)
    r0 = blobs[0][1]
    script = "\n".join([
        "set terminal pngcairo size 720,480 font ',11'" if subprocess.run(
            ["gnuplot", "-e", "set terminal pngcairo"], capture_output=True).returncode == 0
        else "set terminal png size 720,480",
        "set output '%s'" % png,
        "set logscale xy",
        "set xlabel 'blobs N'",
        "set ylabel 'microseconds per primary ray (frame time / pixels)'",
        "set title 'N-blob scene, %dx%d, 1 spp, %d threads (median of %d)'" % (
            r0["width"], r0["height"], r0["threads"], r0["repeat"]),
        "set key top left",
        "set grid",
        "$d << EOD", data, "EOD",
        "plot $d using 1:2 with linespoints lw 2 pt 7 title 'softtrace (bench frame time)', "
        "$d using 1:3 with linespoints lw 2 pt 5 title 'POV-Ray 3.7 blob (Trace Time)'", ""])
    subprocess.run(["gnuplot"], input=script.encode(), check=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--cases", default="blob10,blob100,blob1000,blob10000,fig12b",
                    help="comma-separated; 'real' is the real-world-like set: " + REAL_WORLD)
    ap.add_argument("--width", type=int, default=160)
    ap.add_argument("--height", type=int, default=120)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--max-gradient", type=float, default=0.4,
                    help="POV's max_gradient for fig12b (it reports 0.354 found at 640x480)")
    ap.add_argument("--accuracy", type=float, default=0.001, help="POV's isosurface accuracy")
    ap.add_argument("--settle", type=float, default=1.0,
                    help="idle seconds before every timed process (default 1)")
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--work", default="/tmp/pov_compare", help="scenes and images go here")
    ap.add_argument("--json", help="also write the results here")
    ap.add_argument("--plot", help="also plot the blob cases' time per ray here (PNG)")
    a = ap.parse_args()
    exe = os.path.join(a.build, "softtrace")
    if not os.access(exe, os.X_OK):
        sys.exit("pov_compare: %s: no softtrace there (build first, or pass --build)" % exe)
    install_missing()
    check_pil()
    os.makedirs(a.work, exist_ok=True)
    cases = a.cases.replace("real", REAL_WORLD).split(",")
    bases = {c: write_case(c, a, a.work) for c in cases}
    runs = {c: {"st": [], "pov": []} for c in cases}
    for r in range(a.repeat):
        for c in cases:
            print("round %d/%d: %s" % (r + 1, a.repeat, c), file=sys.stderr)
            turns = [("st", lambda: softtrace(a, bases[c] + ".json", bases[c] + "_st.png")),
                     ("pov", lambda: povray(a, bases[c] + ".pov", bases[c] + "_pov.png"))]
            for who, run in (turns if r % 2 == 0 else reversed(turns)):
                runs[c][who].append(run())

    results = []
    rays = a.width * a.height
    print("%dx%d, 1 spp, %d threads, medians of %d interleaved rounds, %g s idle before each process"
          % (a.width, a.height, a.threads, a.repeat, a.settle))
    print("%-10s %6s %6s %9s %9s %9s %9s %8s %8s %8s %8s" % (
        "case", "IoU", "mean", "st frame", "st proc", "pov trace", "pov proc", "trace/", "proc/",
        "evals/", "us/ray"))
    print("%-10s %6s %6s %9s %9s %9s %9s %8s %8s %8s %8s" % (
        "", "", "/255", "s", "s", "s", "s", "st proc", "st proc", "entered", "st|pov"))
    for c in cases:
        st, pov = runs[c]["st"], runs[c]["pov"]
        med = lambda rs, k: statistics.median(x[k] for x in rs)  # noqa: E731
        res = {"case": c, "width": a.width, "height": a.height, "threads": a.threads,
               "repeat": a.repeat, "commit": st[0]["commit"],
               "iou": iou(coverage(bases[c] + "_st.png"), coverage(bases[c] + "_pov.png")),
               "mean_diff_255": mean_difference(bases[c] + "_st.png", bases[c] + "_pov.png"),
               "st_frame_s": med(st, "frame_s"), "st_process_s": med(st, "process_s"),
               "st_process_cpu_s": med(st, "process_cpu_s"),
               "pov_trace_s": med(pov, "trace_s"), "pov_process_s": med(pov, "process_s"),
               "pov_process_cpu_s": med(pov, "process_cpu_s"),
               "primary": st[0]["primary"], "shadow": st[0]["shadow"],
               "pov_gradient_found": pov[0]["gradient_found"]}
        res["st_us_per_ray"] = res["st_frame_s"] / rays * 1e6
        res["pov_us_per_ray"] = res["pov_trace_s"] / rays * 1e6
        if c == "fig12b":
            povray(a, bases[c] + "_safe.pov", bases[c] + "_safe.png")
            m1, m2 = coverage(bases[c] + "_pov.png"), coverage(bases[c] + "_safe.png")
            res["pov_max_gradient"] = a.max_gradient
            res["pov_pixels_differing_from_safe"] = sum(1 for x, y in zip(m1, m2) if x != y)
        results.append(res)
        print("%-10s %6.4f %6.2f %9.4f %9.4f %9.4f %9.4f %8.2f %8.2f %8.1f %s" % (
            c, res["iou"], res["mean_diff_255"], res["st_frame_s"], res["st_process_s"], res["pov_trace_s"],
            res["pov_process_s"], res["pov_trace_s"] / res["st_process_s"],
            res["pov_process_s"] / res["st_process_s"], res["primary"]["evaluations"],
            "%.2f|%.2f" % (res["st_us_per_ray"], res["pov_us_per_ray"])))
        if c == "fig12b":
            print("%-10s POV max_gradient %g: %d pixels differ from max_gradient %g%s" % (
                "", a.max_gradient, res["pov_pixels_differing_from_safe"], SAFE_MAX_GRADIENT,
                "" if res["pov_gradient_found"] is None else
                " (POV warns: found %g)" % res["pov_gradient_found"]))
    if a.plot:
        plot(results, a.plot)
    # segtrace's POV-Ray blob is a fit of another kernel: its IoU measures the fit, not a fault.
    bad = [r["case"] for r in results if r["iou"] < 0.999 and r["case"] != "segtrace"]
    if bad:
        print("silhouettes differ (IoU < 0.999): " + ", ".join(bad))
    if a.json:
        with open(a.json, "w") as f:
            json.dump(results, f, indent=1)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
