"""Make docs/explorer.png, the README's picture of ``fcgrasp serve`` on ``demo:blob``, and
docs/explorer-real.png, the page on a real drawing (ezdxf's ``forms.dxf`` from the
benchmark corpus: 900 edges of fillets, holes and slots), zoomed on a corner, and
docs/explorer-solid.png, the 3-D view of ``demo:prism`` planned for three fingers with
friction (needs Debian's chromium and chromedriver, as the browser tests do):

    .venv/bin/python docs/make_screenshot.py
"""

from __future__ import annotations

import subprocess
import sys
import tempfile
import time
from pathlib import Path

from selenium import webdriver
from selenium.webdriver.chrome.service import Service

DOCS = Path(__file__).resolve().parent
OUT = DOCS / "explorer.png"
REAL = DOCS / "explorer-real.png"
SOLID = DOCS / "explorer-solid.png"
DRAWING = DOCS.parent / "benchmarks" / "corpus" / "dxf" / "forms.dxf"


def wait_plan(d, after: int) -> None:
    while int(d.execute_script("return document.body.dataset.planSeq")) <= after or \
            d.execute_script("return document.body.dataset.busy") != "0":
        time.sleep(0.05)


def main() -> None:
    proc = subprocess.Popen([sys.executable, "-m", "fcgrasp", "serve", "demo:blob", "--port",
                             "0"], stdout=subprocess.PIPE, text=True)
    url = proc.stdout.readline().split()[2]
    opts = webdriver.ChromeOptions()
    opts.binary_location = "/usr/bin/chromium"
    for arg in ("--headless=new", "--no-sandbox", "--disable-gpu", "--no-first-run",
                "--disable-background-networking", "--disable-component-update",
                "--window-size=1200,760", "--force-device-scale-factor=1",
                "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
                f"--user-data-dir={tempfile.mkdtemp()}"):
        opts.add_argument(arg)
    d = webdriver.Chrome(options=opts, service=Service("/usr/bin/chromedriver"))
    try:
        d.get(url)
        wait_plan(d, 0)
        d.execute_script("document.getElementById('overlay').click()")
        time.sleep(0.3)
        d.save_screenshot(str(OUT))
        d.execute_script("document.getElementById('overlay').click()")
        seq = int(d.execute_script("return document.body.dataset.planSeq"))
        d.find_element("id", "file").send_keys(str(DRAWING))
        wait_plan(d, seq)
        time.sleep(0.3)
        d.save_screenshot(str(REAL))
        seq = int(d.execute_script("return document.body.dataset.planSeq"))
        d.execute_script("const g = document.getElementById('gripper'); g.value = '3'; "
                         "g.dispatchEvent(new Event('change'));"
                         "const m = document.getElementById('mu'); m.value = '0.5'; "
                         "m.dispatchEvent(new Event('change'));"
                         "const s = document.getElementById('demo'); s.value = 'prism'; "
                         "s.dispatchEvent(new Event('change'));")
        wait_plan(d, seq)
        while not d.execute_script("const S = explorer.state; return S.solid && S.plans.length "
                                   "&& S.plans[0].contact_type === 'friction' && "
                                   "document.body.dataset.busy === '0';"):
            time.sleep(0.05)
        time.sleep(0.3)
        d.save_screenshot(str(SOLID))
    finally:
        d.quit()
        proc.terminate()
    print(f"wrote {OUT}, {REAL} and {SOLID}")


if __name__ == "__main__":
    main()
