"""Make docs/explorer.png, the README's picture of ``fcgrasp serve`` (needs Debian's
chromium and chromedriver, as the browser tests do):

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

OUT = Path(__file__).resolve().parent / "explorer.png"


def main() -> None:
    proc = subprocess.Popen([sys.executable, "-m", "fcgrasp", "serve", "demo:blob", "--port",
                             "0"], stdout=subprocess.PIPE, text=True)
    url = proc.stdout.readline().split()[2]
    opts = webdriver.ChromeOptions()
    opts.binary_location = "/usr/bin/chromium"
    for arg in ("--headless=new", "--no-sandbox", "--disable-gpu", "--no-first-run",
                "--disable-background-networking", "--disable-component-update",
                "--window-size=1200,760", "--force-device-scale-factor=1",
                f"--user-data-dir={tempfile.mkdtemp()}"):
        opts.add_argument(arg)
    d = webdriver.Chrome(options=opts, service=Service("/usr/bin/chromedriver"))
    try:
        d.get(url)
        while d.execute_script("return document.body.dataset.planSeq") == "0":
            time.sleep(0.05)
        d.find_element("id", "overlay").click()
        time.sleep(0.3)
        d.save_screenshot(str(OUT))
    finally:
        d.quit()
        proc.terminate()
    print(f"wrote {OUT}")


if __name__ == "__main__":
    main()
