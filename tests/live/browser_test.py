"""The live preview in a real browser: headless Chromium loads the page while vkrt
renders, sees the image change at least twice, shows the render's own figures, and
its Stop button ends the render with a valid output file. Then `vkrt converge
--serve` draws its curves in the page as it measures them, one colour each.

    browser_test.py VKRT SOURCE_DIR"""
import json
import os
import subprocess
import sys
import tempfile
import time

from selenium import webdriver
from selenium.webdriver.chrome.service import Service
from selenium.webdriver.common.by import By

from live_lib import check, fail, png_size, start_vkrt

vkrt, source = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
WIDTH, HEIGHT = 200, 150


def chromium():
    options = webdriver.ChromeOptions()
    options.binary_location = "/usr/bin/chromium"
    for flag in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage"):
        options.add_argument(flag)
    options.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    return webdriver.Chrome(service=Service("/usr/bin/chromedriver"), options=options)


def wait_for(what, predicate, seconds):
    deadline = time.time() + seconds
    while time.time() < deadline:
        value = predicate()
        if value:
            return value
        time.sleep(0.1)
    fail(f"waited {seconds} s for {what}")


with tempfile.TemporaryDirectory() as work:
    scene = os.path.join(source, "scenes", "gallery", "k_room.json")
    size = ["--width", str(WIDTH), "--height", str(HEIGHT)]
    # A reference for the error curve: another seed, so not the render's own samples.
    subprocess.run([vkrt, "render", scene, *size, "--spp", "256", "--seed", "99", "-q", "-o", "ref.exr"], cwd=work,
                   check=True)
    proc, url = start_vkrt(vkrt, ["render", scene, *size, "--time", "300", "--serve", "0", "--reference", "ref.exr",
                                  "-o", "out.png", "--stats", "stats.json"], work)
    browser = chromium()
    try:
        browser.get(url)
        text = lambda element_id: browser.find_element(By.ID, element_id).text

        # The image element loads at least two different images as the render goes.
        sources = set()

        def two_images():
            shown = browser.execute_script(
                "const i = document.getElementById('image');"
                "return [i.currentSrc, i.complete, i.naturalWidth, i.naturalHeight, Number(i.dataset.updates)];")
            if shown[1] and shown[2] == WIDTH and shown[3] == HEIGHT:
                sources.add(shown[0])
            return len(sources) >= 2 and shown[4] >= 2

        wait_for("two images in the page", two_images, 120)
        check(text("backend") == "vulkan", f"backend shown as '{text('backend')}'")
        check(text("state") == "rendering", f"state shown as '{text('state')}' during the render")

        # With a reference, the page draws the error against time: a visible plot
        # with the render's curve in it, from at least two points.
        def plotted():
            return browser.execute_script(
                "const c = document.getElementById('plot');"
                "if (getComputedStyle(c).display === 'none') return false;"
                "const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;"
                "let coloured = 0;"
                "for (let i = 0; i < d.length; i += 4) if (d[i + 3] > 0 && d[i + 2] > 150 && d[i] < 80) coloured++;"
                "return coloured;")

        wait_for("the error curve in the plot", lambda: (plotted() or 0) > 50, 60)
        time.sleep(3)
        if os.environ.get("VKRT_LIVE_SCREENSHOT"):
            browser.set_window_size(1000, 900)
            browser.save_screenshot(os.environ["VKRT_LIVE_SCREENSHOT"])

        browser.find_element(By.ID, "stop").click()
        wait_for("the page to show the render stopped", lambda: text("state").startswith("stopped"), 60)
        code = proc.wait(timeout=60)
        check(code == 0, f"vkrt exited with {code} after Stop:\n{open(os.path.join(work, 'stderr.txt')).read()}")

        # What the page shows at the end is what the render's statistics say.
        stats = json.load(open(os.path.join(work, "stats.json")))
        shown = {k: text(k) for k in ("samples", "passes", "rays", "mrays", "backend", "device", "output")}
        expected = {
            "samples": str(stats["samples_per_pixel"]),
            "passes": str(stats["passes"]),
            "rays": str(stats["rays"]["total"]),
            "mrays": f"{stats['rays_per_second'] * 1e-6:.2f}",
            "backend": stats["backend"],
            "device": stats["device"],
            "output": "out.png",
        }
        check(shown == expected, f"the page shows {shown}, the render's statistics say {expected}")
        check(stats["stopped_by_request"] and not stats["stopped_by_time"], "the stats do not say Stop ended it")
        check(text("target") == "(until the time is up)", f"target shown as '{text('target')}'")

        # The output is a whole PNG of the image size, readable by vkrt itself.
        out = os.path.join(work, "out.png")
        check(png_size(out) == (WIDTH, HEIGHT), f"out.png is {png_size(out)}, not {WIDTH}x{HEIGHT}")
        compare = subprocess.run([vkrt, "compare", out, out], capture_output=True, text=True)
        check(compare.returncode == 0, f"vkrt compare cannot read out.png: {compare.stderr}")

        # The page broke no rule of its own security policy and threw nothing.
        errors = [e for e in browser.get_log("browser") if e["level"] == "SEVERE"]
        check(not errors, f"the browser reported errors: {errors}")
        browser.quit()

        # converge: two curves, drawn as they are measured, with the points of its CSV.
        proc, url = start_vkrt(vkrt, ["converge", scene, *size, "--reference", "ref.exr", "--spp", "32",
                                      "--estimator", "path+nee", "--estimator", "path", "--serve", "0",
                                      "--csv", "curves.csv", "-q"], work)
        browser = chromium()
        browser.get(url)
        curves = wait_for("two curves in the plot", lambda: browser.execute_script(
            "const c = document.getElementById('plot');"
            "if (getComputedStyle(c).display === 'none') return 0;"
            "const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;"
            "let blue = 0, red = 0;"
            "for (let i = 0; i < d.length; i += 4) {"
            "  if (d[i] === 31 && d[i + 1] === 119 && d[i + 2] === 180) blue++;"
            "  if (d[i] === 214 && d[i + 1] === 39 && d[i + 2] === 40) red++;"
            "}"
            "return blue > 50 && red > 50;"), 120)
        wait_for("the page to show converge finished", lambda: text("state").startswith("finished"), 120)
        code = proc.wait(timeout=60)
        check(code == 0, f"vkrt converge exited with {code}:\n{open(os.path.join(work, 'stderr.txt')).read()}")
        rows = open(os.path.join(work, "curves.csv")).read().split()[1:]
        check(len(rows) == 12, f"curves.csv has {len(rows)} rows, expected 2 curves of 6 checkpoints")
        print(f"ok: {len(sources)} images shown, stopped at {stats['samples_per_pixel']} spp, "
              f"{stats['passes']} passes, figures as in the stats")
    finally:
        browser.quit()
        if proc.poll() is None:
            proc.kill()
