"""The grasp explorer in a real browser: Debian's headless Chromium driven by Selenium
through Debian's ChromeDriver (installed by ``python3 tasks.py test``), against
``fcgrasp serve`` started as a user would start it.

The page's plans must agree with ``fcgrasp plan`` on the part the page holds, after a
load, a drag and a change of mu; hand-placed fingers get the verdict of ``fcgrasp check``;
a screenshot shows each region in its finger's colour where the plan says it is."""

from __future__ import annotations

import io
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("selenium")
pytest.importorskip("starlette")

from selenium import webdriver  # noqa: E402
from selenium.common.exceptions import TimeoutException  # noqa: E402
from selenium.webdriver.chrome.service import Service  # noqa: E402
from selenium.webdriver.common.action_chains import ActionChains  # noqa: E402
from selenium.webdriver.common.by import By  # noqa: E402

from fcgrasp.apps.cli import main  # noqa: E402

from .test_serve import _star  # noqa: E402

CHROMIUM = shutil.which("chromium") or "/usr/bin/chromium"
DRIVER = shutil.which("chromedriver") or "/usr/bin/chromedriver"
COLORS = [(0xd6, 0x27, 0x28), (0x1f, 0x77, 0xb4), (0x2c, 0xa0, 0x2c), (0x94, 0x67, 0xbd)]

pytestmark = pytest.mark.skipif(
    not (os.path.exists(CHROMIUM) and os.path.exists(DRIVER)),
    reason="Debian's chromium and chromium-driver are not installed (python3 tasks.py test "
           "installs them with apt-get)")


@pytest.fixture(scope="module")
def server():
    proc = subprocess.Popen([sys.executable, "-m", "fcgrasp", "serve", "demo:blob", "--port",
                             "0"], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    line = proc.stdout.readline()
    if "http://" not in line:
        proc.kill()
        pytest.fail(f"fcgrasp serve did not start: {line!r} {proc.stderr.read()!r}")
    url = line.split()[2]
    yield url
    proc.terminate()
    proc.wait(10)


@pytest.fixture(scope="module")
def downloads():
    with tempfile.TemporaryDirectory(prefix="fcgrasp-dl-") as d:
        yield Path(d)


@pytest.fixture(scope="module")
def browser(downloads):
    opts = webdriver.ChromeOptions()
    opts.binary_location = CHROMIUM
    profile = tempfile.mkdtemp(prefix="fcgrasp-chromium-")
    for arg in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-quic",
                "--no-first-run", "--disable-background-networking",
                "--disable-component-update", "--disable-sync", "--window-size=1300,850",
                "--force-device-scale-factor=1", f"--user-data-dir={profile}",
                # WebGL (a solid's 3-D view) in software, with no GPU
                "--use-angle=swiftshader", "--enable-unsafe-swiftshader"):
        opts.add_argument(arg)
    opts.add_experimental_option("prefs", {"download.default_directory": str(downloads),
                                           "download.prompt_for_download": False})
    os.environ.setdefault("SE_OFFLINE", "true")      # never let Selenium fetch a driver
    driver = webdriver.Chrome(options=opts, service=Service(DRIVER))
    yield driver
    driver.quit()
    shutil.rmtree(profile, ignore_errors=True)


#: How often the page polls a condition :func:`wait` waits for (ms).
POLL_MS = 10


def wait(driver, script, timeout=600.0):
    """Wait until a JavaScript expression is truthy; its value.  The page polls it
    (every :data:`POLL_MS`) and answers once: one round trip to the browser per wait,
    not one per poll (each a few milliseconds of the browser's, the driver's and this
    process's time).  An error the expression raises is raised here."""
    driver.set_script_timeout(timeout)
    try:
        got = driver.execute_async_script(f"""
            const done = arguments[arguments.length - 1];
            const poll = () => {{
              let value;
              try {{ value = ({script}); }} catch (e) {{ done({{error: String(e)}}); return; }}
              if (value) done({{value: value}}); else setTimeout(poll, {POLL_MS});
            }};
            poll();""")
    except TimeoutException:
        raise AssertionError(f"timed out waiting for {script}") from None
    if "error" in got:
        raise AssertionError(f"{script} raised {got['error']}")
    return got["value"]


def plan_seq(driver):
    return int(driver.execute_script("return document.body.dataset.planSeq"))


def wait_plan(driver, after):
    # (document.body is null for a moment while a page loads under a busy machine)
    wait(driver, f"document.body && Number(document.body.dataset.planSeq) > {after} && "
                 f"document.body.dataset.busy === '0'")


def page_plans(driver):
    items = driver.find_elements(By.CSS_SELECTOR, "#plans li")
    return [(li.get_attribute("data-edges"), float(li.get_attribute("data-min")))
            for li in items]


def cli_report(tmp_path, driver, argv):
    part = driver.execute_script("return explorer.state.part")
    path = tmp_path / "page-part.json"
    path.write_text(json.dumps({"vertices": part["outer"], "holes": part["holes"]}))
    out = tmp_path / "cli.json"
    assert main(["plan", str(path), "--no-clean", "--json", str(out), "--quiet", *argv]) == 0
    return json.loads(out.read_text())


def cli_plans(tmp_path, driver, argv):
    report = cli_report(tmp_path, driver, argv)
    return [(",".join(map(str, g["edges"])), g["min_region_length"]) for g in report["grasps"]]


def drawn_regions_are(driver, grasp):
    """The bold polylines on the page are the regions of ``grasp`` (a plan of
    ``fcgrasp plan --json``), point for point on the screen."""
    lines = driver.find_elements(By.CSS_SELECTOR, "#plan polyline.region")
    assert len(lines) == len(grasp["regions"])
    for line, region in zip(lines, grasp["regions"], strict=True):
        drawn = np.array([[float(v) for v in p.split(",")]
                          for p in line.get_attribute("points").split()])
        want = np.array(driver.execute_script(
            "return arguments[0].map((p) => explorer.toScreen(p));", region))
        assert drawn.shape == want.shape and np.allclose(drawn, want, atol=0.01)


def same_plans(a, b):
    assert [e for e, _ in a] == [e for e, _ in b]
    assert np.allclose([m for _, m in a], [m for _, m in b], rtol=1e-9)


def set_value(driver, element_id, value):
    driver.execute_script("const e = document.getElementById(arguments[0]); e.value = "
                          "arguments[1]; e.dispatchEvent(new Event('change'));",
                          element_id, str(value))


def screen_point(driver, p):
    """Viewport coordinates (CSS pixels) of a part point ``p``."""
    return driver.execute_script(
        "const q = explorer.toScreen(arguments[0]); const r = document.getElementById('view')"
        ".getBoundingClientRect(); return [r.left + q[0], r.top + q[1]];", list(p))


def click_at(driver, xy):
    body = driver.find_element(By.TAG_NAME, "body")
    ActionChains(driver).move_to_element_with_offset(
        body, xy[0] - body.rect["width"] / 2, xy[1] - body.rect["height"] / 2).click().perform()


def open_demo(driver, server, name):
    """The page, then the built-in part ``name`` picked from its list and planned."""
    from selenium.webdriver.support.ui import Select

    driver.get(server)
    # the page's first plan done (not merely not yet begun): only the pick's plan is left
    wait_plan(driver, 0)
    after = plan_seq(driver)
    Select(driver.find_element(By.ID, "demo")).select_by_value(name)
    wait_plan(driver, after)


def test_plans_load_drag_and_mu_agree_with_fcgrasp_plan(server, browser, tmp_path):
    from PIL import Image

    browser.get(server)
    wait_plan(browser, 0)
    same_plans(page_plans(browser), cli_plans(tmp_path, browser, ["--mu", "0.3"]))
    assert browser.find_element(By.CSS_SELECTOR, "#plans li.selected").get_attribute(
        "data-rank") == "1"
    # two fingers' plans are a parallel gripper's: their MoveIt grasps are offered
    assert browser.find_element(By.ID, "export-moveit").is_enabled()
    assert browser.execute_script("return explorer.state.moveit.length") == \
        len(page_plans(browser))

    # the screenshot: each region of plan 1 drawn in its finger's colour along the plan's
    # polyline, and the part's grey inside the outline
    png = browser.get_screenshot_as_png()
    shot = Path(tmp_path / "explorer.png")
    shot.write_bytes(png)
    img = np.asarray(Image.open(io.BytesIO(png)).convert("RGB")).astype(int)
    plan = browser.execute_script("return explorer.state.plans[0]")
    for i, reg in enumerate(plan["regions"]):
        reg = np.asarray(reg)
        for t in (0.3, 0.5, 0.7):
            p = reg[0] + t * (reg[-1] - reg[0]) if len(reg) == 2 else reg[len(reg) // 2]
            x, y = screen_point(browser, p)
            patch = img[int(round(y)) - 1:int(round(y)) + 2, int(round(x)) - 1:int(round(x)) + 2]
            dist = np.abs(patch - np.array(COLORS[i])).sum(axis=2).min()
            assert dist < 40, (i, t, patch.tolist())
    cx, cy = screen_point(browser, browser.execute_script(
        "return [explorer.state.part.outer.reduce((a, p) => a + p[0], 0) / 6,"
        " explorer.state.part.outer.reduce((a, p) => a + p[1], 0) / 6]"))
    assert np.abs(img[int(cy), int(cx)] - 224).max() <= 3        # the part's fill, #e0e0e0
    # away from the regions nothing is in a finger's colour: the drawing is not a smear
    reds = (np.abs(img - np.array(COLORS[0])).sum(axis=2) < 40).sum()
    assert 0 < reds < 0.01 * img.shape[0] * img.shape[1]

    # drag vertex 2 by (30, -20) pixels: the part follows, the plans are those of the new part
    seq = plan_seq(browser)
    before = browser.execute_script("return explorer.state.part.outer[2]")
    scale = browser.execute_script("return explorer.state.view.s")
    handle = browser.find_element(By.CSS_SELECTOR, 'circle.vertex[data-ring="0"]'
                                                   '[data-index="2"]')
    ActionChains(browser).drag_and_drop_by_offset(handle, 30, -20).perform()
    wait_plan(browser, seq)
    after = browser.execute_script("return explorer.state.part.outer[2]")
    assert np.allclose(np.subtract(after, before), [30 / scale, 20 / scale], atol=2 / scale)
    same_plans(page_plans(browser), cli_plans(tmp_path, browser, ["--mu", "0.3"]))

    # mu 0.6: new plans, still those of fcgrasp plan
    seq = plan_seq(browser)
    set_value(browser, "mu", 0.6)
    wait_plan(browser, seq)
    same_plans(page_plans(browser), cli_plans(tmp_path, browser, ["--mu", "0.6"]))
    # the drawing is the CLI's best plan; picking plan 2 in the list draws plan 2
    report = cli_report(tmp_path, browser, ["--mu", "0.6"])
    drawn_regions_are(browser, report["grasps"][0])
    browser.find_elements(By.CSS_SELECTOR, "#plans li")[1].click()
    wait(browser, "document.getElementById('plan').dataset.rank === '2'")
    drawn_regions_are(browser, report["grasps"][1])

    # a drag that makes the outline cross itself: a message, and the last good outline kept
    good = browser.execute_script("return explorer.state.part.outer")
    handle = browser.find_element(By.CSS_SELECTOR, 'circle.vertex[data-ring="0"]'
                                                   '[data-index="0"]')
    x0, y0 = screen_point(browser, good[0])
    x3, y3 = screen_point(browser, good[3])
    ActionChains(browser).drag_and_drop_by_offset(handle, (x3 - x0) * 1.3,
                                                  (y3 - y0) * 1.3).perform()
    wait(browser, "document.getElementById('message').textContent.includes('crossed')")
    assert browser.execute_script("return explorer.state.part.outer") == good

    # undo: back to the outline before the drag, planned again
    seq = plan_seq(browser)
    browser.find_element(By.ID, "undo").click()
    wait_plan(browser, seq)
    assert np.allclose(browser.execute_script("return explorer.state.part.outer[2]"), before)
    same_plans(page_plans(browser), cli_plans(tmp_path, browser, ["--mu", "0.6"]))


def test_fingers_by_hand_verdict_and_escape(server, browser, tmp_path):
    browser.get(server)
    wait_plan(browser, 0)
    plan = browser.execute_script("return explorer.state.plans[0]")
    browser.find_element(By.ID, "mode-fingers").click()
    for c in plan["contacts"]:          # the plan's own grasp: force closure
        click_at(browser, screen_point(browser, c))
    wait(browser, "document.getElementById('verdict').dataset.closure === 'yes'")
    assert "force closure" in browser.find_element(By.ID, "verdict").text

    # the same fingers checked by fcgrasp check
    fingers = browser.execute_script("return explorer.state.fingers")
    part = browser.execute_script("return explorer.state.part")
    (tmp_path / "p.json").write_text(json.dumps({"vertices": part["outer"]}))
    (tmp_path / "c.json").write_text(json.dumps({"contacts": [
        {"point": f["point"], "edge": f["edge"], "mu": 0.3} for f in fingers]}))
    assert main(["check", str(tmp_path / "p.json"), "--no-clean", "--contacts",
                 str(tmp_path / "c.json"), "--quiet"]) == 0

    # take the second finger away (click it) and put it beside the first: not closure,
    # the reason is said and the escape motion animated
    finger = browser.find_element(By.CSS_SELECTOR, 'circle.finger[data-finger="1"]')
    finger.click()
    wait(browser, "explorer.state.fingers.length === 1")
    e = fingers[0]["edge"]
    a, b = np.asarray(part["outer"][e]), np.asarray(part["outer"][(e + 1) % len(part["outer"])])
    click_at(browser, screen_point(browser, a + 0.8 * (b - a)))
    wait(browser, "document.getElementById('verdict').dataset.closure === 'no'")
    text = browser.find_element(By.ID, "verdict").text
    assert "closure fails" in text and "escape" in text
    ghost = wait(browser, "document.getElementById('ghost').getAttribute('transform')")
    assert ghost.startswith(("rotate", "translate"))
    assert browser.execute_script("return document.getElementById('ghost').getAttribute('d')")


def test_load_a_file_export_and_cancel(server, browser, downloads, tmp_path):
    browser.get(server)
    wait_plan(browser, 0)
    # a file in another format: an SVG of the rectangle
    svg = tmp_path / "plate.svg"
    svg.write_text('<svg xmlns="http://www.w3.org/2000/svg" width="80mm" height="30mm" '
                   'viewBox="0 0 80 30"><rect x="0" y="0" width="80" height="30"/></svg>')
    seq = plan_seq(browser)
    browser.find_element(By.ID, "file").send_keys(str(svg))
    wait_plan(browser, seq)
    assert "plate.svg" in browser.find_element(By.ID, "partinfo").text
    same_plans(page_plans(browser), cli_plans(tmp_path, browser, ["--mu", "0.3"]))

    # an unreadable file: a message, the part kept
    bad = tmp_path / "bad.json"
    bad.write_text("{not json")
    browser.find_element(By.ID, "file").send_keys(str(bad))
    wait(browser, "document.getElementById('message').textContent.includes('bad.json')")
    assert "plate.svg" in browser.find_element(By.ID, "partinfo").text

    # exports: the plan JSON is the server's report; the SVG figure has the regions
    browser.find_element(By.ID, "export-json").click()
    browser.find_element(By.ID, "export-svg").click()
    end = time.monotonic() + 600            # a hung browser only
    while time.monotonic() < end and not ((downloads / "fcgrasp-plan.json").exists()
                                          and (downloads / "fcgrasp-plan.svg").exists()):
        time.sleep(0.1)
    report = json.loads((downloads / "fcgrasp-plan.json").read_text())
    assert report["grasps"] == browser.execute_script("return explorer.state.report.grasps")
    figure = (downloads / "fcgrasp-plan.svg").read_text()
    assert figure.count('class="region"') == len(report["grasps"][0]["regions"])
    assert 'class="vertex"' not in figure

    # a slow plan (three fingers on 1,500 edges: tens of seconds, so it cannot end
    # before the click, however busy the machine) shows progress and is cancelled
    big = tmp_path / "big.json"
    big.write_text(json.dumps({"vertices": _star(1500).tolist()}))
    set_value(browser, "gripper", "3")
    browser.find_element(By.ID, "distinct").click()     # the ranked search's batches
    browser.find_element(By.ID, "file").send_keys(str(big))
    # the big part shown (the sidebar's layout settled) and its plan under way
    wait(browser, "document.getElementById('partinfo').textContent.includes('big.json')"
                  " && document.getElementById('statustext').textContent.includes('/')")
    browser.find_element(By.ID, "cancel").click()
    wait(browser, "document.body.dataset.busy === '0'")
    assert browser.find_element(By.ID, "statustext").text == "cancelled"


def d_part(n_arc=1999):
    """A half disc (radius 50) whose arc is flattened into ``n_arc`` edges, with a square
    hole: 2,003 edges, six corners (two on the outline, four in the hole)."""
    a = np.linspace(0.0, np.pi, n_arc + 1)
    outer = np.c_[50 * np.cos(a), 50 * np.sin(a)]
    hole = [[-5, 15], [-5, 25], [5, 25], [5, 15]]
    return {"vertices": outer.round(9).tolist(), "holes": [hole]}


def move_to(driver, xy):
    body = driver.find_element(By.TAG_NAME, "body")
    ActionChains(driver).move_to_element_with_offset(
        body, xy[0] - body.rect["width"] / 2, xy[1] - body.rect["height"] / 2).perform()


def wheel(driver, xy, delta_y):
    """A wheel event over the drawing at viewport point ``xy``."""
    driver.execute_script(
        "document.getElementById('view').dispatchEvent(new WheelEvent('wheel', {clientX: "
        "arguments[0], clientY: arguments[1], deltaY: arguments[2], bubbles: true, "
        "cancelable: true}));", xy[0], xy[1], delta_y)


def screen_state(driver):
    """Handles, edge numbers' boxes and the outline's edges, in the drawing's pixels."""
    return driver.execute_script("""
        const S = explorer.state, R = [S.part.outer, ...S.part.holes];
        const segs = [];
        R.forEach((r) => r.forEach((p, i) => {
          segs.push([explorer.toScreen(p), explorer.toScreen(r[(i + 1) % r.length])]);
        }));
        return {
          handles: [...document.querySelectorAll('.handle circle.vertex')].map((c) =>
            [+c.dataset.ring, +c.dataset.index, +c.getAttribute('cx'), +c.getAttribute('cy')]),
          labels: [...document.querySelectorAll('.labels text')].map((t) => {
            const b = t.getBBox(); return [+t.dataset.edge, b.x, b.y, b.x + b.width,
                                           b.y + b.height]; }),
          segs, view: S.view,
          regions: S.plans.length ? S.plans[S.selected].regions.map((r) =>
            r.map((p) => explorer.toScreen(p))) : []};""")


def _boxes_clear(labels, segs, regions=()):
    """No two numbers' boxes overlap, no edge of the outline crosses a number, and no
    region (a bold line, 7 pixels wide) covers one."""
    boxes = np.array([b[1:] for b in labels])
    for i in range(len(boxes)):
        a = boxes[i]
        other = boxes[i + 1:]
        assert not np.any((other[:, 0] < a[2]) & (a[0] < other[:, 2]) & (other[:, 1] < a[3])
                          & (a[1] < other[:, 3])), labels[i]
    segs = np.asarray(segs, float)                         # (m, 2, 2)
    t = np.linspace(0.0, 1.0, 65)[:, None, None]
    pts = segs[None, :, 0] + t * (segs[None, :, 1] - segs[None, :, 0])   # (65, m, 2)
    pts = pts.reshape(-1, 2)
    for b in boxes:
        inside = (pts[:, 0] > b[0] + 0.5) & (pts[:, 0] < b[2] - 0.5) & \
            (pts[:, 1] > b[1] + 0.5) & (pts[:, 1] < b[3] - 0.5)
        assert not inside.any(), b
    for line in regions:
        line = np.asarray(line, float)
        pts = (line[:-1, None] + t[:, :, 0][None] * (line[1:, None] - line[:-1, None]))
        pts = pts.reshape(-1, 2)
        for b in boxes:
            assert not ((pts[:, 0] > b[0] - 3.5) & (pts[:, 0] < b[2] + 3.5)
                        & (pts[:, 1] > b[1] - 3.5) & (pts[:, 1] < b[3] + 3.5)).any(), b


@pytest.mark.slow       # the default suite's time
def test_a_real_part_handles_numbers_scale_zoom_and_pan(server, browser, tmp_path):
    """A 2,003-edge part is drawn for a person, not as a chain of beads."""
    browser.get(server)
    wait_plan(browser, 0)
    path = tmp_path / "half-disc.json"
    path.write_text(json.dumps(d_part()))
    # the ranked list (distinct alternatives of two fingers along a 2,000-edge arc read
    # thousands of shifted copies, about ten seconds; not what this test is about)
    seq = plan_seq(browser)
    browser.find_element(By.ID, "distinct").click()
    wait_plan(browser, seq)
    seq = plan_seq(browser)
    browser.find_element(By.ID, "file").send_keys(str(path))
    wait_plan(browser, seq)
    gap = browser.execute_script("return HANDLE_GAP")
    st = screen_state(browser)
    handles = np.array([h[2:] for h in st["handles"]])
    # handles: at every corner, never closer than the gap, a few dozen on the curve
    d = np.hypot(*(handles[:, None] - handles[None]).transpose(2, 0, 1))
    assert d[~np.eye(len(d), dtype=bool)].min() >= gap - 1e-6
    assert len(handles) < 150
    taken = {(h[0], h[1]) for h in st["handles"]}
    assert {(0, 0), (0, 1999), (1, 0), (1, 1), (1, 2), (1, 3)} <= taken

    # edge numbers: some placed (the flat side's among them), none overlapping a number
    # or the outline
    numbers = [lab[0] for lab in st["labels"]]
    assert 1999 in numbers and len(numbers) >= 5
    _boxes_clear(st["labels"], st["segs"], st["regions"])
    browser.find_element(By.ID, "edgenums").click()
    assert not browser.find_elements(By.CSS_SELECTOR, ".labels text")
    browser.find_element(By.ID, "edgenums").click()

    # the scale bar: a round length in the part's units, as long as the view says
    bar = browser.find_element(By.ID, "scalebar")
    length, pixels = float(bar.get_attribute("data-length")), float(
        bar.get_attribute("data-pixels"))
    mant = length / 10 ** np.floor(np.log10(length))
    assert min(abs(mant - k) for k in (1, 2, 5)) < 1e-9
    assert 60 <= pixels <= 150 and abs(pixels - length * st["view"]["s"]) < 1e-2
    assert bar.text.endswith("mm")

    # zoom about the pointer: the part's point under it stays put
    r = browser.execute_script("return document.getElementById('view')"
                               ".getBoundingClientRect().toJSON()")
    # (a wheel event's clientX and clientY are whole pixels)
    x, y = np.round(screen_point(browser, [50 * np.cos(1.2), 50 * np.sin(1.2)]))
    on_arc = browser.execute_script("return explorer.toPart(arguments[0], arguments[1])",
                                    x - r["left"], y - r["top"])
    s0 = st["view"]["s"]
    for _ in range(6):
        wheel(browser, (x, y), -400)
    s1 = browser.execute_script("return explorer.state.view.s")
    assert s1 / s0 == pytest.approx(np.exp(6 * 400 * 0.0015), rel=1e-9)
    under = browser.execute_script("return explorer.toPart(arguments[0], arguments[1])",
                                   x - r["left"], y - r["top"])
    assert np.allclose(under, on_arc, atol=1e-6 * 50)
    # zoomed in this far, the curve's vertices in view are far enough apart: each has one
    st = screen_state(browser)
    part = browser.execute_script("return explorer.state.part")
    q = np.array(browser.execute_script(
        "return explorer.state.part.outer.map((p) => explorer.toScreen(p))"))
    view = st["view"]
    seen = [i for i, (qx, qy) in enumerate(q)
            if -gap <= qx <= view["W"] + gap and -gap <= qy <= view["H"] + gap]
    assert len(seen) >= 20 and set(seen) == {h[1] for h in st["handles"] if h[0] == 0}
    _boxes_clear(st["labels"], st["segs"], st["regions"])
    assert len(st["labels"]) >= 5

    # pan: dragging the background moves the view by the drag, the scale unchanged
    o0 = browser.execute_script("return [explorer.state.view.ox, explorer.state.view.oy]")
    bg = (r["left"] + 20, r["top"] + 60)
    body = browser.find_element(By.TAG_NAME, "body")
    ActionChains(browser).move_to_element_with_offset(
        body, bg[0] - body.rect["width"] / 2, bg[1] - body.rect["height"] / 2) \
        .click_and_hold().move_by_offset(20, 10).move_by_offset(20, 15).release().perform()
    o1 = browser.execute_script("return [explorer.state.view.ox, explorer.state.view.oy]")
    assert np.allclose(np.subtract(o1, o0), [40, 25], atol=1.0)
    assert browser.execute_script("return explorer.state.view.s") == pytest.approx(s1)

    # fit view, then the pointer on a vertex of the curve: a handle there, the readout
    # names the edge
    browser.find_element(By.ID, "fit").click()
    v = part["outer"][700]
    move_to(browser, screen_point(browser, v))
    hover = wait(browser, "document.querySelector('#hover circle.vertex')")
    k = int(hover.get_attribute("data-index"))       # vertices 0.7 pixels apart here
    assert abs(k - 700) <= 2
    assert re.search(rf"edge ({k - 1}|{k})$", browser.find_element(By.ID, "readout").text)


def _crosses_itself(rings):
    """Whether two edges that share no vertex cross properly (every pair of edges of
    every ring, in numpy: the reference the page's O(n) drag check must agree with)."""
    a = np.concatenate([np.asarray(r, float) for r in rings])
    b = np.concatenate([np.roll(np.asarray(r, float), -1, axis=0) for r in rings])
    ring = np.concatenate([np.full(len(r), k) for k, r in enumerate(rings)])
    idx = np.concatenate([np.arange(len(r)) for r in rings])
    size = np.array([len(rings[k]) for k in ring])

    def side(pts):                         # [j, i]: pts[i] against edge j (a cross product)
        e, d = b - a, pts[None, :, :] - a[:, None, :]
        return e[:, None, 0] * d[..., 1] - e[:, None, 1] * d[..., 0]
    s, t = side(a), side(b)
    # edge i's ends on both sides of edge j's line, strictly (and the other way round)
    split = ((s > 0) != (t > 0)) & (s != 0) & (t != 0)
    proper = split & split.T
    gap = np.abs(idx[:, None] - idx[None, :])
    near = (ring[:, None] == ring[None, :]) & ((gap <= 1) | (gap == size[:, None] - 1))
    return bool((proper & ~near).any())


def test_the_drag_check_is_the_whole_outline_check(server, browser):
    """The drag's self-crossing test (the two edges at the moved vertex against the
    rest, O(n)) gives the verdict of the test of every pair of edges (in numpy here), on
    seeded random moves of a star with a hole, crossings and near misses included."""
    browser.get(server)
    wait_plan(browser, 0)
    rng = np.random.default_rng(5)
    verdicts = set()
    for trial in range(40):
        outer = _star(60, seed=trial).tolist()
        hole = (0.2 * np.asarray(outer[::6])).tolist()
        ring = int(rng.integers(0, 2))
        r = outer if ring == 0 else hole
        i = int(rng.integers(0, len(r)))
        if trial % 2:                          # anywhere over the part: crossings
            r[i] = rng.uniform(-80, 80, 2).tolist()
        else:                                  # near its place: near misses
            r[i] = (np.asarray(r[i]) * rng.uniform(0.0, 2.5) + rng.normal(0, 5, 2)).tolist()
        fast = browser.execute_script(
            "return explorer.crossesAt({outer: arguments[0], holes: [arguments[1]]},"
            " arguments[2], arguments[3]);", outer, hole, ring, i)
        whole = _crosses_itself([outer, hole])
        assert fast == whole, (trial, ring, i)
        verdicts.add(whole)
    assert verdicts == {True, False}            # both kinds of move were met


# ----------------------------------------------------------------------------- solids

_REGION_COLOURS = """
    const S = explorer.state, v = explorer.solid3d, plan = S.plans[S.selected];
    const eye = v.state().eye;
    return plan.regions.map((r, k) => {
      const c = plan.centers[k], n = plan.normals[k];     // the report's: outward
      const out = n[0] * (eye[0] - c[0]) + n[1] * (eye[1] - c[1]) + n[2] * (eye[2] - c[2]);
      // a point of the region between its centre (under the contact's marker) and a corner
      const p = [0, 1, 2].map((i) => c[i] + 0.6 * (r[0][i] - c[i]));
      const q = v.project(p);
      return {facing: out > 0, pixel: v.pixel(q[0], q[1])};
    });"""


def _colours_right(driver):
    """Each region of the selected plan whose facet faces the camera shows its finger's
    colour (red, blue, green: shaded) on the canvas; one facing away shows none."""
    seen = driver.execute_script(_REGION_COLOURS)
    for k, s in enumerate(seen):
        px = s["pixel"][:3]
        ch = (0, 2, 1)[k]                     # red, blue, green: COLORS of the page
        others = max(v for i, v in enumerate(px) if i != ch)
        if s["facing"]:
            assert px[ch] > 1.3 * others + 10, (k, s)
    return [s["facing"] for s in seen]


_SURFACE_COLOURS = """
    const S = explorer.state, v = explorer.solid3d, plan = S.plans[S.selected];
    const eye = v.state().eye;
    return plan.surface_triangles.map((tris, k) => {
      const n = plan.normals[k];                           // the report's: outward
      return tris.map((t) => {
        const c = [0, 1, 2].map((i) => (t[0][i] + t[1][i] + t[2][i]) / 3);
        const out = n[0] * (eye[0] - c[0]) + n[1] * (eye[1] - c[1]) + n[2] * (eye[2] - c[2]);
        const q = v.project(c);
        return {facing: out > 0, pixel: v.pixel(q[0], q[1])};
      });
    });"""


@pytest.mark.slow       # the default suite's time: the solid's turn and plan stay
def test_regions_across_facets_are_drawn_on_the_mugs_wall(server, browser, tmp_path):
    """``demo:mug`` in the explorer: its plans are ``fcgrasp plan``'s, regions across the
    facets of its wall first; each region is drawn by its own triangles on the curved
    surface, in its finger's colour where it faces the camera (and the handle does not
    hide it)."""
    d = browser
    open_demo(d, server, "mug")
    assert d.execute_script("return explorer.solid3d.state().error") is None
    mu = d.execute_script("return document.getElementById('mu').value")
    out = tmp_path / "mug.json"
    assert main(["plan", "demo:mug", "--fingers", "2", "--soft", "--mu", str(mu),
                 "--top", "10", "--json", str(out), "--quiet"]) == 0
    want = json.loads(out.read_text())["grasps"]
    items = d.find_elements(By.CSS_SELECTOR, "#plans li")
    assert np.allclose([float(li.get_attribute("data-radius")) for li in items],
                       [g["radius"] for g in want], rtol=1e-9)
    assert want[0].get("across_facets")
    seen = d.execute_script(_SURFACE_COLOURS)
    shown = 0
    for k, region in enumerate(seen):
        ch = (0, 2, 1)[k]                     # red, blue: COLORS of the page
        for s in region:
            px = s["pixel"][:3]
            if s["facing"] and px[ch] > 1.3 * max(v for i, v in enumerate(px) if i != ch) + 10:
                shown += 1
    # (a region's triangle may face the camera and still lie behind the handle)
    facing = sum(s["facing"] for region in seen for s in region)
    assert facing and shown >= 0.3 * facing, (shown, facing)


@pytest.mark.slow
def test_a_solid_plans_in_3d_turns_and_goes_back_to_the_plane(server, browser, downloads,
                                                              tmp_path):
    """A built-in solid in the explorer: its plans are those of ``fcgrasp plan demo:box
    --fingers 2 --soft``; the WebGL view shows each region in its finger's colour where
    the plan puts it; a drag turns the part (the far region comes into view), the wheel
    comes closer; the point-finger grippers that never hold a solid are disabled; a
    planar part brings the outline back."""
    from selenium.webdriver.support.ui import Select

    d = browser
    open_demo(d, server, "box")
    assert d.execute_script("return explorer.solid3d.state().error") is None
    assert d.find_element(By.ID, "view3d").is_displayed()
    assert not d.find_element(By.ID, "view").is_displayed()
    disabled = d.execute_script("return [...document.getElementById('gripper').options]"
                                ".filter((o) => o.disabled).map((o) => o.value)")
    assert disabled == ["3g", "4"]
    out = tmp_path / "box.json"
    assert main(["plan", "demo:box", "--fingers", "2", "--soft", "--mu", "0.3", "--top", "10",
                 "--json", str(out), "--quiet"]) == 0
    want = json.loads(out.read_text())["grasps"]
    items = d.find_elements(By.CSS_SELECTOR, "#plans li")
    assert [li.get_attribute("data-facets") for li in items] == \
        [",".join(map(str, g["facets"])) for g in want]
    assert np.allclose([float(li.get_attribute("data-radius")) for li in items],
                       [g["radius"] for g in want], rtol=1e-9)
    facing = _colours_right(d)
    assert facing.count(True) == 1            # opposite facets: one faces the camera
    # a drag half a turn across turns the part: the other region faces the camera
    canvas = d.find_element(By.ID, "view3d")
    yaw = d.execute_script("return explorer.solid3d.state().yaw")
    ActionChains(d).move_to_element(canvas).click_and_hold().move_by_offset(157, 0) \
        .move_by_offset(157, 0).release().perform()
    turned = d.execute_script("return explorer.solid3d.state().yaw")
    assert turned == pytest.approx(yaw - 3.14, abs=1e-6)
    assert _colours_right(d) == [not f for f in facing]
    dist = d.execute_script("return explorer.solid3d.state().dist")
    d.execute_script("document.getElementById('view3d').dispatchEvent(new WheelEvent('wheel', "
                     "{deltaY: -300, bubbles: true, cancelable: true}));")
    assert d.execute_script("return explorer.solid3d.state().dist") < dist
    items[1].click()
    _colours_right(d)
    # the view as a picture: the canvas's pixels
    from PIL import Image

    png = downloads / "fcgrasp-view.png"
    png.unlink(missing_ok=True)
    d.find_element(By.ID, "export-png").click()
    end = time.monotonic() + 600            # a hung browser only
    while not png.exists() and time.monotonic() < end:
        time.sleep(0.05)
    size = d.execute_script("const c = document.getElementById('view3d'); "
                            "return [c.width, c.height];")
    with Image.open(png) as im:
        assert list(im.size) == size
    assert not d.find_element(By.ID, "export-svg").is_displayed()
    # the view faces as many regions as it can: three fingers on the sides of a prism
    # (a report's normals point out of the part)
    outward = [[np.cos(a), np.sin(a), 0.0] for a in (0.3, 0.3 + 2.1, 0.3 + 4.2)]
    assert d.execute_script("return explorer.solid3d.aim({normals: arguments[0]});", outward)
    st = d.execute_script("return explorer.solid3d.state()")
    view = np.array([np.cos(st["pitch"]) * np.cos(st["yaw"]),
                     np.cos(st["pitch"]) * np.sin(st["yaw"]), np.sin(st["pitch"])])
    assert sum(float(view @ np.array(n)) > 0.2 for n in outward) == 2
    # distinct alternatives only (ticked, every gripper's default): the page asks for
    # --distinct 0.5; unticked, for every plan as ranked
    assert d.execute_script("return explorer.state.report.parameters.distinct") == 0.5
    after = plan_seq(d)
    d.find_element(By.ID, "distinct").click()
    wait_plan(d, after)
    assert d.execute_script("return explorer.state.report.parameters.distinct") is None
    d.find_element(By.ID, "distinct").click()
    # back to a planar part: the outline, every gripper
    after = plan_seq(d)
    Select(d.find_element(By.ID, "demo")).select_by_value("quad")
    wait_plan(d, after)
    assert d.find_element(By.ID, "view").is_displayed()
    assert not d.find_element(By.ID, "view3d").is_displayed()
    assert d.execute_script("return [...document.getElementById('gripper').options]"
                            ".every((o) => !o.disabled)")
    assert d.find_elements(By.CSS_SELECTOR, "#plans li")[0].get_attribute("data-edges")


@pytest.mark.slow       # the default suite's time
def test_the_optimality_bound_is_shown_as_fcgrasp_plan_prints_it(server, browser, tmp_path):
    """"prove how far from the optimum" (``--bound``) is offered for three fingers with
    friction and four frictionless fingers only; checked, the page prints the line
    ``fcgrasp plan --bound`` prints for the same part and options."""
    import contextlib

    from selenium.webdriver.support.ui import Select

    d = browser
    open_demo(d, server, "triangle")
    assert not d.find_element(By.ID, "bound").is_displayed()      # two fingers
    after = plan_seq(d)
    set_value(d, "mu", 0.5)
    Select(d.find_element(By.ID, "gripper")).select_by_value("3")
    wait_plan(d, after)
    assert d.find_element(By.ID, "bound").is_displayed()
    # three fingers' plans are not a parallel gripper's: no MoveIt grasps to export
    assert not d.find_element(By.ID, "export-moveit").is_enabled()
    assert not d.find_element(By.ID, "optimum").is_displayed()   # empty until asked
    after = plan_seq(d)
    d.find_element(By.ID, "bound").click()
    wait_plan(d, after)
    wait(d, "document.getElementById('optimum').textContent.length > 0")
    shown = d.find_element(By.ID, "optimum").text
    argv = ["--fingers", "3", "--mu", "0.5", "--bound"]
    part = d.execute_script("return explorer.state.part")
    path = tmp_path / "triangle.json"
    path.write_text(json.dumps({"vertices": part["outer"], "holes": part["holes"]}))
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        assert main(["plan", str(path), "--no-clean", "--units", part["units"], *argv]) == 0
    line = next(x for x in out.getvalue().splitlines() if x.startswith("optimum:"))
    assert shown == line
    # unchecked: no line; four frictionless fingers: offered too; the jaw: not
    after = plan_seq(d)
    d.find_element(By.ID, "bound").click()
    wait_plan(d, after)
    assert not d.find_element(By.ID, "optimum").is_displayed()
    after = plan_seq(d)
    Select(d.find_element(By.ID, "gripper")).select_by_value("4")
    wait_plan(d, after)
    assert d.find_element(By.ID, "bound").is_displayed()
    Select(d.find_element(By.ID, "gripper")).select_by_value("jaw")
    assert not d.find_element(By.ID, "bound").is_displayed()
    # each gripper's default distinct= (0.5 for every gripper): picking one ticks
    # 'distinct alternatives only' again after a user unticked it
    assert d.find_element(By.ID, "distinct").is_selected()
    d.find_element(By.ID, "distinct").click()
    assert not d.find_element(By.ID, "distinct").is_selected()
    Select(d.find_element(By.ID, "gripper")).select_by_value("4")
    assert d.find_element(By.ID, "distinct").is_selected()


def test_the_3d_view_triangulates_regions_that_are_not_convex(server, browser):
    """A jaw's region can be an L (``demo:angle``'s caps): the view cuts each region into
    triangles by ear clipping; on seeded star-shaped polygons, in tilted planes, either
    way round, the triangles cover the polygon exactly (their areas add up to its area,
    each lies inside it)."""
    import shapely

    d = browser
    if not d.current_url.startswith(server):
        d.get(server)
    wait(d, "window.explorer && explorer.solid3d")
    rng = np.random.default_rng(3)
    for _ in range(40):
        n = int(rng.integers(3, 12))
        a = np.sort(rng.uniform(0, 2 * np.pi, n))
        r = rng.uniform(0.3, 1.0, n)
        flat = np.c_[r * np.cos(a), r * np.sin(a)][::rng.choice([1, -1])]
        poly = shapely.Polygon(flat)
        if not poly.is_valid:
            continue
        # the polygon in a random plane: axes u, v and normal w
        w = rng.normal(size=3)
        w /= np.linalg.norm(w)
        u = np.cross(w, [1.0, 0.0, 0.0] if abs(w[0]) < 0.9 else [0.0, 1.0, 0.0])
        u /= np.linalg.norm(u)
        v = np.cross(w, u)
        pts = flat[:, :1] * u + flat[:, 1:] * v + rng.normal(size=3)
        tris = d.execute_script("return explorer.solid3d.triangulate(arguments[0], "
                                "arguments[1]);", pts.tolist(), w.tolist())
        assert len(tris) == n - 2
        area = 0.0
        for t in tris:
            tri = shapely.Polygon(flat[t])
            area += tri.area
            assert poly.buffer(1e-9).contains(tri), (flat.tolist(), t)
        assert area == pytest.approx(poly.area, rel=1e-9)


def test_a_page_of_another_origin_can_neither_read_nor_plan(server, browser, tmp_path):
    """A web page the user visits (served here from another port of the loopback: another
    origin) tries the explorer's API as a hostile page would: it cannot read the part or
    the page (the browser's same-origin policy, and the server grants no CORS), and its
    no-cors text/plain POST, which the browser does send, carries no session token, so
    the server refuses it (tests/test_serve.py checks that refusal starts no job).  The
    explorer's own page still plans."""
    import http.server
    import threading

    (tmp_path / "evil.html").write_text(f"""<!doctype html><title>evil</title><script>
    const E = {json.dumps(server)};
    const out = {{}};
    async function go() {{
      for (const [k, url] of [["state", E + "api/state"], ["page", E],
                               ["part", E + "api/demo/blob"]]) {{
        try {{ const r = await fetch(url); out[k] = "read " + (await r.text()).length; }}
        catch (e) {{ out[k] = "blocked"; }}
      }}
      try {{
        const r = await fetch(E + "api/plan", {{method: "POST", mode: "no-cors",
          headers: {{"Content-Type": "text/plain"}},
          body: JSON.stringify({{part: {{outer: [[0, 0], [10, 0], [0, 10]]}}, options: {{}}}})}});
        out.plan = r.type;
      }} catch (e) {{ out.plan = "blocked"; }}
      document.body.dataset.out = JSON.stringify(out);
    }}
    go();
    </script><body></body>""")

    class Quiet(http.server.SimpleHTTPRequestHandler):
        def __init__(self, *a, **k):
            super().__init__(*a, directory=str(tmp_path), **k)

        def log_message(self, *a):
            pass

    evil = http.server.ThreadingHTTPServer(("127.0.0.1", 0), Quiet)
    threading.Thread(target=evil.serve_forever, daemon=True).start()
    try:
        browser.get(f"http://127.0.0.1:{evil.server_address[1]}/evil.html")
        out = json.loads(wait(browser, "document.body.dataset.out"))
    finally:
        evil.shutdown()
    assert out["state"] == out["page"] == out["part"] == "blocked", out
    assert out["plan"] in ("opaque", "blocked"), out
    # the explorer's own page plans as before
    browser.get(server)
    wait(browser, "document.body.dataset.planSeq !== undefined && "
                  "Number(document.body.dataset.planSeq) > 0")
    assert page_plans(browser)


@pytest.mark.slow       # the default suite's time
def test_a_file_of_several_parts_offers_them_and_sizes_the_jaw(server, browser, tmp_path):
    """A drawing of two parts: the page takes the largest, lists both (as fcgrasp parts
    does) and takes the other when it is picked; the jaw's stroke and pads follow the
    part's size until the user sets them."""
    import ezdxf
    from selenium.webdriver.support.ui import Select

    doc = ezdxf.new()
    doc.header["$INSUNITS"] = 4
    msp = doc.modelspace()
    msp.add_lwpolyline([(0, 0), (4, 0), (4, 4), (0, 4)], close=True)
    msp.add_lwpolyline([(10, 0), (40, 0), (30, 20), (10, 20)], close=True)
    path = tmp_path / "two.dxf"
    doc.saveas(path)
    browser.get(server)
    wait_plan(browser, 0)                 # the page's first plan done
    before = plan_seq(browser)
    browser.find_element(By.ID, "file").send_keys(str(path))
    wait(browser, "document.body.dataset.parts === 'many'")
    wait_plan(browser, before)
    pick = Select(browser.find_element(By.ID, "partpick"))
    assert len(pick.options) == 2
    assert "4 edges" in browser.find_element(By.ID, "partinfo").text
    size = browser.execute_script("return explorer.state.part.outer.length")
    assert size == 4
    big = float(browser.find_element(By.ID, "stroke1").get_attribute("value"))
    other = next(o.get_attribute("value") for o in pick.options if not o.is_selected())
    before = plan_seq(browser)
    pick.select_by_value(other)
    # the other part read (the small square: 4 mm across)
    wait(browser, "(() => { const xs = explorer.state.part.outer.map((p) => p[0]); "
                  "return Math.max(...xs) - Math.min(...xs) < 5; })()")
    wait_plan(browser, before)
    outer = np.array(browser.execute_script("return explorer.state.part.outer"))
    assert np.allclose(np.ptp(outer, axis=0), [4, 4])          # the small square
    small = float(browser.find_element(By.ID, "stroke1").get_attribute("value"))
    assert small < big                                           # sized to the part


def test_the_time_limit_stops_the_search_and_the_page_says_so(server, browser, tmp_path):
    """The page's time limit reaches the search (``--time-limit``): a search it stops
    shows the plans proved and why it stopped, as fcgrasp plan prints it."""
    from .test_serve import _smooth

    path = tmp_path / "smooth.json"
    path.write_text(json.dumps({"vertices": _smooth()}))
    browser.get(server)
    wait_plan(browser, 0)
    # the options set without a change event: the upload's plan is the only one to read them
    browser.execute_script("document.getElementById('timelimit').value = '0.01';"
                           "document.getElementById('mu').value = '1.0';")
    before = plan_seq(browser)
    browser.find_element(By.ID, "file").send_keys(str(path))
    wait(browser, "document.getElementById('partinfo').textContent.includes('smooth.json')")
    wait_plan(browser, before)
    report = browser.execute_script("return explorer.state.report")
    assert report["complete"] is False and report["gap"]["stopped_by"] == "time_limit"
    text = browser.find_element(By.ID, "incomplete").text
    assert text.startswith("search stopped at its time limit (--time-limit): "
                           f"{report['gap']['found']} of 10 plans proved")


def test_a_real_hand_is_drawn_at_each_boxs_pose(server, browser):
    """The jaw with a built-in hand: the page sends the hand's name (never a file), the
    plans come with poses, and the hand's boxes are drawn around the pads; held in the
    plate's plane, likewise."""
    from selenium.webdriver.support.ui import Select

    d = browser
    open_demo(d, server, "rectangle")           # a page of its own: no earlier test's options
    after = plan_seq(d)
    Select(d.find_element(By.ID, "gripper")).select_by_value("jaw")
    wait_plan(d, after)
    after = plan_seq(d)
    Select(d.find_element(By.ID, "hand")).select_by_value("franka")
    wait_plan(d, after)
    report = d.execute_script("return explorer.state.report;")
    assert report["hand"]["name"] == "franka" and report["parameters"]["stroke"] == [0, 79.96]
    assert report["grasps"] and all("pose" in g for g in report["grasps"])
    boxes = d.find_elements(By.CSS_SELECTOR, "#plan .hand-box")
    assert len(boxes) == len(report["hand"]["boxes"])
    # held in the plate's plane: the plans of fcgrasp plan --in-plane, the hand drawn at
    # each pose (its approach in the plane)
    after = plan_seq(d)
    d.find_element(By.ID, "inplane").click()
    wait_plan(d, after)
    answer = d.execute_script("return explorer.state.report;")
    assert answer["scene"]["held"] == "in_plane" and answer["grasps"]
    assert all(g["held"] == "in_plane" and g["approach"]["direction"][2] == 0
               for g in answer["grasps"])
    assert len(d.find_elements(By.CSS_SELECTOR, "#plan .hand-box")) == \
        len(answer["hand"]["boxes"])
    after = plan_seq(d)
    d.find_element(By.ID, "inplane").click()
    wait_plan(d, after)
    after = plan_seq(d)
    Select(d.find_element(By.ID, "hand")).select_by_value("")
    wait_plan(d, after)
    assert not d.find_elements(By.CSS_SELECTOR, "#plan .hand-box")


@pytest.mark.slow       # the default suite's time: the hand drawn in 2-D stays
def test_a_solids_pick_shows_the_hand_the_table_axes_and_a_scale_in_3d(server, browser):
    """A solid picked from a table by the Franka Hand: the 3-D view (three.js, vendored
    from npm) draws the hand's boxes at the selected plan's pose, the table the part
    rests on, the part frame's axes and a scale bar of a round length; a plan without a
    hand draws neither hand nor table."""
    from selenium.webdriver.support.ui import Select

    d = browser
    open_demo(d, server, "cylinder")
    st = d.execute_script("return explorer.solid3d.state()")
    assert st["error"] is None and st["library"].startswith("three.js r")
    assert {"axes", "scale"} <= set(st["drawn"]) and "hand-box" not in st["drawn"]
    size = d.execute_script("return explorer.state.solid.size")
    assert st["scale"]["length"] <= size / 3 and st["scale"]["units"] == "mm"
    assert str(st["scale"]["length"]).lstrip("0.").rstrip("0") in ("1", "2", "5")
    assert d.find_element(By.ID, "scale3d").text.startswith(f"scale bar {st['scale']['length']:g}")
    after = plan_seq(d)
    Select(d.find_element(By.ID, "gripper")).select_by_value("jaw")
    wait_plan(d, after)
    after = plan_seq(d)
    d.execute_script("document.getElementById('table').checked = true;")
    Select(d.find_element(By.ID, "hand")).select_by_value("franka")
    wait_plan(d, after)
    report = d.execute_script("return explorer.state.report;")
    assert report["hand"]["name"] == "franka" and report["scene"]["table"] is not None
    assert report["grasps"] and all("pose" in g for g in report["grasps"])
    drawn = d.execute_script("return explorer.solid3d.state().drawn")
    # each box drawn as a translucent solid and its edges
    assert drawn.count("hand-box") == 2 * len(report["hand"]["boxes"])
    assert "table" in drawn


@pytest.mark.slow
def test_the_selected_plan_is_shaken_in_mujoco(server, browser):
    """The stress test button: the selected plan's grasps shaken on the server
    (``/api/stress``, ``fcgrasp simulate``'s), how many held, and the animation."""
    pytest.importorskip("mujoco")
    d = browser
    open_demo(d, server, "rectangle")
    wait(d, "!document.getElementById('stress').disabled")
    d.find_element(By.ID, "stress").click()
    text = wait(d, "document.getElementById('stresstext').textContent.includes('held') && "
                   "document.getElementById('stresstext').textContent", timeout=600)
    assert text.startswith("plan 1: ") and "of 4 grasps held" in text, text
    assert int(d.execute_script("return document.body.dataset.stressHeld")) >= 3
    assert d.find_element(By.ID, "stressgif").is_displayed()
    assert d.find_element(By.ID, "stressgif").get_attribute("src").startswith(
        "data:image/gif;base64,")
