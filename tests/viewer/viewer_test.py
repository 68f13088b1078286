#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""The replay page in a real browser: headless Chromium driven by Selenium (both Debian packages:
chromium, chromium-driver, python3-selenium). Loads the page that `impulse view` writes, checks that
it starts, steps the time slider with the keyboard, plays, takes a screenshot, and fails on any
error the page logs.

    viewer_test.py --impulse BUILD/impulse --scenes SCENES_DIR --probe BUILD/impulse_png_probe --work DIR
"""
import argparse
import os
import shutil
import subprocess
import sys
import tempfile
import time

from selenium import webdriver
from selenium.webdriver.chrome.service import Service
from selenium.webdriver.common.by import By
from selenium.webdriver.common.keys import Keys

WIDTH, HEIGHT = 1200, 800
failures = []


def check(condition, what):
    print(("ok: " if condition else "FAIL: ") + what, flush=True)
    if not condition:
        failures.append(what)


def run(*command):
    result = subprocess.run(command, capture_output=True, text=True, timeout=120)
    if result.returncode != 0:
        sys.exit("command failed (%d): %s\n%s" % (result.returncode, " ".join(command), result.stderr))
    return result


def wait_for(driver, script, what, seconds=20):
    deadline = time.time() + seconds
    while time.time() < deadline:
        if driver.execute_script(script):
            return True
        time.sleep(0.05)
    check(False, what)
    return False


def browser(profile):
    options = webdriver.ChromeOptions()
    options.binary_location = shutil.which("chromium") or "/usr/bin/chromium"
    for flag in ("--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                 "--disable-background-networking", "--disable-component-update", "--disable-sync",
                 "--enable-unsafe-swiftshader", "--user-data-dir=" + profile,
                 # containers often give /dev/shm only 64 MB, too little for Chromium's renderer
                 "--disable-dev-shm-usage",
                 "--window-size=%d,%d" % (WIDTH, HEIGHT)):
        options.add_argument(flag)
    options.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    service = Service(shutil.which("chromedriver") or "/usr/bin/chromedriver")
    return webdriver.Chrome(service=service, options=options)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--impulse", required=True)
    parser.add_argument("--scenes", required=True)
    parser.add_argument("--probe", required=True)
    parser.add_argument("--work", required=True)
    args = parser.parse_args()
    os.makedirs(args.work, exist_ok=True)

    # two bodies, a ground-free scene: the oblique collision, 5 s every 10 ms; playing takes 5 s, time
    # enough to pause it before it ends however slow the machine
    scene = os.path.join(args.scenes, "ball_ball_oblique.json")
    csv = os.path.join(args.work, "oblique.csv")
    page = os.path.join(args.work, "oblique.html")
    run(args.impulse, "run", scene, "--duration", "5", "--every", "10", "--out", csv)
    run(args.impulse, "view", csv, "--scene", scene, "--out", page)
    with open(page, encoding="utf-8") as file:
        html = file.read()
    check("<script src" not in html and "http://" not in html.split("impulse-data")[0],
          "the page loads nothing from elsewhere")

    profile = tempfile.mkdtemp(prefix="impulse-chromium-")
    driver = browser(profile)
    try:
        driver.get("file://" + os.path.abspath(page))
        if wait_for(driver, "return window.impulseViewer && window.impulseViewer.ready", "the viewer starts"):
            frames = driver.execute_script("return impulseViewer.frameCount()")
            check(frames == 501, "501 samples in the page (got %s)" % frames)
            start = driver.execute_script("return impulseViewer.bodyPosition(0)")

            slider = driver.find_element(By.ID, "slider")
            slider.click()  # focus; a click also moves the thumb, so go back to the start with Home
            slider.send_keys(Keys.HOME)
            for _ in range(5):
                slider.send_keys(Keys.ARROW_RIGHT)
            frame = driver.execute_script("return impulseViewer.frame()")
            check(frame == 5, "five right-arrow presses on the slider show sample 5 (got %s)" % frame)
            moved = driver.execute_script("return impulseViewer.bodyPosition(0)")
            check(abs(moved[0] - start[0] - 0.05) < 1e-3,
                  "body 0 moved 0.05 m along x at 1 m/s (from %s to %s)" % (start[0], moved[0]))
            clock = driver.find_element(By.ID, "clock").text
            check(clock == "t = 0.050 s", "the clock reads t = 0.050 s (got %r)" % clock)

            driver.find_element(By.ID, "play").click()
            wait_for(driver, "return impulseViewer.frame() > 15", "playing advances the time")
            driver.find_element(By.ID, "play").click()
            paused_at = driver.execute_script("return impulseViewer.frame()")
            time.sleep(0.3)
            check(not driver.execute_script("return impulseViewer.playing()") and
                  driver.execute_script("return impulseViewer.frame()") == paused_at, "pause stops playing")

            slider.send_keys(Keys.END)
            check(driver.execute_script("return impulseViewer.frame()") == 500, "End shows the last sample")

            shot = os.path.join(args.work, "viewer_screenshot.png")
            check(driver.save_screenshot(shot), "screenshot saved")
            probe = subprocess.run([args.probe, shot], capture_output=True, text=True)
            fields = probe.stdout.split()
            check(probe.returncode == 0 and len(fields) == 3, "the screenshot decodes as a PNG (%s)" %
                  (probe.stdout.strip() or probe.stderr.strip()))
            if len(fields) == 3:
                width, height, spread = int(fields[0]), int(fields[1]), float(fields[2])
                check(width == WIDTH, "screenshot width %d is the window's %d" % (width, WIDTH))
                check(spread > 10.0, "the screenshot is not blank (pixel standard deviation %.1f)" % spread)
            errors = driver.execute_script("return impulseViewer.errors")
            check(not errors, "no uncaught errors in the page: %s" % errors)

        logs = driver.get_log("browser")
        for entry in logs:
            print("console %s: %s" % (entry["level"], entry["message"]))
        severe = [entry for entry in logs if entry["level"] == "SEVERE"]
        check(not severe, "the page logs no error (%d logged)" % len(severe))
    finally:
        driver.quit()
        shutil.rmtree(profile, ignore_errors=True)

    if failures:
        sys.exit("%d check(s) failed:\n  %s" % (len(failures), "\n  ".join(failures)))


if __name__ == "__main__":
    main()
