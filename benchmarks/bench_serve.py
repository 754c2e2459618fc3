"""How fast the explorer (``fcgrasp serve``) answers, for parts of 6, 50, 200 and 2,000
edges (the target: every interaction within 100 ms on the 2,000-edge part).

Server side: each request timed from the client over loopback against ``fcgrasp serve``
started as a user starts it (median of repeats): the first answer of ``POST /api/plan``
(the result, or a job to poll: the page never waits longer), the time until the plan is
done, ``POST /api/check`` of a three-finger grasp, ``POST /api/part`` of the part as a JSON
file.  Page side (needs Debian's chromium and chromedriver): one frame of a vertex drag
(the self-crossing test and a redraw of everything), timed in the page.

    .venv/bin/python benchmarks/bench_serve.py
"""

from __future__ import annotations

import json
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
import urllib.request

import numpy as np

#: Edges of the parts measured.
SIZES = (6, 50, 200, 2000)
#: The target for an interaction (seconds).
TARGET = 0.1


def star(n: int, seed: int = 1) -> list[list[float]]:
    """A random star of ``n`` edges (radii 50-65: every vertex a spike), up to 200 edges;
    from 1,000 edges a flattened curve with 0.3 % noise, as a real part of that many
    edges is (a random star of 2,000 spikes takes the exact two-finger search 10 s)."""
    rng = np.random.default_rng(seed)
    if n >= 1000:
        a = np.linspace(0, 2 * np.pi, n, endpoint=False)
        r = 50 * (1 + 0.3 * np.sin(5 * a)) * (1 + 0.003 * rng.standard_normal(n))
        return np.c_[r * np.cos(a), r * np.sin(a)].round(6).tolist()
    ang = np.sort(rng.uniform(0, 2 * np.pi, n))
    r = 50 * (1 + 0.3 * rng.random(n))
    return np.c_[r * np.cos(ang), r * np.sin(ang)].round(6).tolist()


#: the session token of a page the server served, as the page sends it (:func:`token`)
TOKEN: dict[str, str] = {}


def token(base: str) -> None:
    """Take a session token from the page, as the browser does."""
    import re

    with urllib.request.urlopen(base) as r:
        html = r.read().decode()
    TOKEN["X-Fcgrasp-Token"] = re.search(r'name="fcgrasp-token" content="([^"]+)"',
                                         html).group(1)


def call(url: str, method: str = "GET", body: bytes | None = None) -> tuple[float, dict]:
    req = urllib.request.Request(url, data=body, method=method,
                                 headers={"Content-Type": "application/json", **TOKEN})
    t0 = time.perf_counter()
    with urllib.request.urlopen(req) as r:
        data = json.loads(r.read())
    return time.perf_counter() - t0, data


def plan_times(base: str, part: dict, options: dict, repeat: int = 5) -> tuple[float, float]:
    first, done = [], []
    body = json.dumps({"part": part, "options": options}).encode()
    for _ in range(repeat):
        t0 = time.perf_counter()
        dt, ans = call(base + "api/plan", "POST", body)
        first.append(dt)
        while ans["state"] == "running":       # as the page polls: a long poll
            _, ans = call(base + f"api/jobs/{ans['job']}?wait=0.1")
        assert ans["state"] == "done", ans
        done.append(time.perf_counter() - t0)
    return statistics.median(first), statistics.median(done)


def page_frame(base: str, n: int) -> float | None:
    """Median time of one drag frame in Chromium (the page's own ``dragVertex``: the
    vertex moved, the outline checked where it changed, everything drawn again), seconds."""
    if not (shutil.which("chromium") and shutil.which("chromedriver")):
        return None
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    opts = webdriver.ChromeOptions()
    opts.binary_location = shutil.which("chromium")
    for arg in ("--headless=new", "--no-sandbox", "--disable-gpu", "--no-first-run",
                "--disable-background-networking", "--disable-component-update",
                "--window-size=1300,850", f"--user-data-dir={tempfile.mkdtemp()}"):
        opts.add_argument(arg)
    d = webdriver.Chrome(options=opts, service=Service(shutil.which("chromedriver")))
    try:
        d.get(base)
        end = time.monotonic() + 60
        while d.execute_script("return document.body.dataset.planSeq") == "0":
            if time.monotonic() > end:
                raise RuntimeError("the page did not plan")
            time.sleep(0.05)
        d.execute_script("explorer.state.part.outer = arguments[0];", star(n))
        ms = d.execute_script("""
            const S = explorer.state, out = [];
            for (let k = 0; k < 30; k++) {
              const t0 = performance.now();
              explorer.dragVertex(0, 0, [S.part.outer[0][0] + 1e-3, S.part.outer[0][1]]);
              out.push(performance.now() - t0);
            }
            S.dragging = false;
            out.sort((a, b) => a - b);
            return out[15];""")
        return float(ms) / 1000
    finally:
        d.quit()


def main() -> None:
    proc = subprocess.Popen([sys.executable, "-m", "fcgrasp", "serve", "demo:blob", "--port",
                             "0"], stdout=subprocess.PIPE, text=True)
    base = proc.stdout.readline().split()[2]
    try:
        token(base)
        rows = []
        for n in SIZES:
            part = {"outer": star(n), "units": "mm"}
            row = {"edges": n}
            for key, opts in (("2f", {"gripper": "2", "mu": 0.3}),
                              ("2f single", {"gripper": "2", "mu": 0.3,
                                             "along_boundary": False}),
                              ("4f single", {"gripper": "4", "along_boundary": False})):
                row[key] = plan_times(base, part, opts)
            contacts = [{"point": p, "type": "friction", "mu": 0.3}
                        for p in (part["outer"][0], part["outer"][n // 3],
                                  part["outer"][2 * n // 3])]
            body = json.dumps({"part": part, "contacts": contacts}).encode()
            row["check"] = statistics.median(call(base + "api/check", "POST", body)[0]
                                             for _ in range(5))
            upload = json.dumps({"vertices": part["outer"]}).encode()
            row["upload"] = statistics.median(call(base + "api/part?name=p.json", "POST",
                                                   upload)[0] for _ in range(5))
            rows.append(row)
        frames = {n: page_frame(base, n) for n in SIZES}
    finally:
        proc.terminate()
        proc.wait(10)

    def ms(v: float | None) -> str:
        return "-" if v is None else f"{1000 * v:.1f}"

    print("fcgrasp serve, times in ms over loopback (median); 'answer' is the first reply of "
          "POST /api/plan (the result, or a job to poll), 'done' the plan's end")
    print()
    print("| edges | 2 fingers answer / done | 2 fingers single-edge answer / done | "
          "4 fingers single-edge answer / done | check (3 fingers) | upload (JSON) | "
          "drag frame in the page |")
    print("| --- | --- | --- | --- | --- | --- | --- |")
    for row in rows:
        n = row["edges"]
        cells = [f"{ms(row[k][0])} / {ms(row[k][1])}" for k in ("2f", "2f single", "4f single")]
        print(f"| {n} | " + " | ".join(cells) + f" | {ms(row['check'])} | "
              f"{ms(row['upload'])} | {ms(frames[n])} |")
    big = next(r for r in rows if r["edges"] == max(SIZES))
    answers = [big[k][1] for k in ("2f", "2f single", "4f single")] + [big["check"],
                                                                       big["upload"]]
    if frames[max(SIZES)] is not None:
        answers.append(frames[max(SIZES)])
    worst = max(answers)
    print()
    print(f"target: every interaction done within {ms(TARGET)} ms on "
          f"{max(SIZES):,} edges (plans to their end): worst {ms(worst)} ms, "
          f"{'met' if worst <= TARGET else 'not met'}")


if __name__ == "__main__":
    main()
