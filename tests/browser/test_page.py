"""The page of `dynosize serve` as a person uses it (docs/web.md): Debian's chromium, headless,
through python3-selenium. Starts `dynosize serve --port 0`, opens the page, runs the drive
calculator on the paper's pair, browses the catalog, loads the quadcopter example, optimizes, and
finds the CLI's pick in the table. A screenshot of each view goes to $DYNOSIZE_SCREENSHOTS (the
README's docs/img/web/ when set so).

Run: DYNOSIZE_EXE=build/dynosize /usr/bin/python3 -m pytest -q tests/browser
Skips (with the reason) when chromium, chromedriver or selenium are missing."""
import json
import os
import shutil
import signal
import subprocess
import time

import pytest

ROOT = os.environ.get("DYNOSIZE_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
EXE = os.environ.get("DYNOSIZE_EXE", os.path.join(ROOT, "build", "dynosize"))
CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
CHROMEDRIVER = shutil.which("chromedriver")

try:
    from selenium import webdriver
    from selenium.webdriver.common.by import By
    from selenium.webdriver.support import expected_conditions as EC
    from selenium.webdriver.support.ui import Select, WebDriverWait
except ImportError:  # pragma: no cover
    webdriver = None

pytestmark = pytest.mark.skipif(
    webdriver is None or not CHROMIUM or not CHROMEDRIVER,
    reason="browser test skipped: needs chromium, chromium-driver and python3-selenium (scripts/setup-debian.sh)")


@pytest.fixture(scope="module")
def server():
    proc = subprocess.Popen([EXE, "serve", "--port", "0", "--quiet"], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)
    line = proc.stdout.readline()
    assert "listening on http://" in line, line + proc.stderr.read()
    url = line.split("listening on ")[1].split()[0]
    yield url
    proc.send_signal(signal.SIGINT)  # Ctrl-C: a clean stop, exit code 0
    assert proc.wait(timeout=20) == 0
    assert "stopped" in proc.stderr.read()


@pytest.fixture(scope="module")
def browser():
    opts = webdriver.ChromeOptions()
    opts.binary_location = CHROMIUM
    for a in ("--headless=new", "--no-sandbox", "--disable-dev-shm-usage", "--disable-gpu", "--window-size=1280,1000"):
        opts.add_argument(a)
    service = webdriver.ChromeService(executable_path=CHROMEDRIVER) if hasattr(webdriver, "ChromeService") else \
        webdriver.chrome.service.Service(executable_path=CHROMEDRIVER)
    driver = webdriver.Chrome(service=service, options=opts)
    yield driver
    driver.quit()


def screenshot(driver, name):
    folder = os.environ.get("DYNOSIZE_SCREENSHOTS")
    if folder:
        os.makedirs(folder, exist_ok=True)
        driver.save_screenshot(os.path.join(folder, name))


def cli_json(*args):
    out = subprocess.run([EXE, *args, "--json"], check=True, capture_output=True, text=True).stdout
    return json.loads(out)


def test_drive_calculator(server, browser):
    t0 = time.monotonic()
    browser.get(server)
    wait = WebDriverWait(browser, 30, poll_frequency=0.02)
    wait.until(lambda d: d.find_element(By.TAG_NAME, "body").get_attribute("data-ready") == "1")
    interactive_s = time.monotonic() - t0
    print(f"page interactive (catalog lists loaded, first table drawn) in {interactive_s:.2f} s")
    assert Select(browser.find_element(By.ID, "motor")).first_selected_option.get_attribute("value") == "emax_1900kv_paper"
    rows = browser.find_elements(By.CSS_SELECTOR, "#drive-table tbody tr")
    assert len(rows) == 10  # 10 % to 100 % throttle
    # The table's thrust at 100 % equals the CLI's for the same request.
    cli = cli_json("simulate", "--motor", "emax_1900kv_paper", "--esc", "multistar_30a_paper", "--vdc", "7.2",
                   "--prop", "fu_p_apc_8x3.8sf")
    cells = rows[-1].find_elements(By.TAG_NAME, "td")
    assert cells[2].text == f"{cli['throttles'][-1]['thrust_n']:.2f}"
    assert cells[4].text == f"{cli['throttles'][-1]['idc_a']:.2f}"
    # A change of voltage redraws the table (a drive-calculator update; its time is printed).
    vdc = browser.find_element(By.ID, "vdc")
    vdc.clear()
    vdc.send_keys("8.4")
    browser.find_element(By.ID, "drive-run").click()
    wait.until(EC.text_to_be_present_in_element((By.ID, "drive-title"), "at 8.4 V"))
    print(f"drive-calculator update: {browser.find_element(By.TAG_NAME, 'body').get_attribute('data-drive-ms')} ms")
    # A bad value shows the CLI's message where it happened.
    vdc.clear()
    vdc.send_keys("-1")
    browser.find_element(By.ID, "drive-run").click()
    wait.until(EC.visibility_of_element_located((By.ID, "drive-error")))
    cli_error = subprocess.run([EXE, "simulate", "--motor", "emax_1900kv_paper", "--esc", "multistar_30a_paper",
                                "--vdc", "-1", "--prop", "fu_p_apc_8x3.8sf", "--json"], capture_output=True, text=True)
    assert cli_error.returncode == 64
    assert browser.find_element(By.ID, "drive-error").text == cli_error.stderr.strip().removeprefix("dynosize: ")
    vdc.clear()
    vdc.send_keys("7.2")
    browser.find_element(By.ID, "drive-run").click()
    wait.until(EC.text_to_be_present_in_element((By.ID, "drive-title"), "at 7.2 V"))
    assert not browser.find_element(By.ID, "drive-error").is_displayed()
    screenshot(browser, "drive_calculator.png")


def test_catalog(server, browser):
    browser.find_element(By.ID, "tab-catalog").click()
    wait = WebDriverWait(browser, 30)
    wait.until(lambda d: len(d.find_elements(By.CSS_SELECTOR, "#cat-table tbody tr")) > 0)
    text = browser.find_element(By.ID, "cat-text")
    text.send_keys("emax_1900kv")
    browser.find_element(By.ID, "cat-run").click()
    wait.until(EC.text_to_be_present_in_element((By.ID, "cat-count"), "1 of"))
    browser.find_element(By.CSS_SELECTOR, "#cat-table tbody tr").click()
    wait.until(EC.presence_of_element_located((By.ID, "cat-entry-values")))
    entry = browser.find_element(By.ID, "cat-entry").text
    assert "tier assumed" in entry
    assert "rm_ohm" in entry and "assumed" in entry and "kv_rpm_per_v" in entry and "datasheet" in entry
    browser.execute_script("document.querySelector('#view-catalog .list').scrollLeft = 0;")  # the click scrolled it
    screenshot(browser, "catalog.png")


def test_mission_optimizer(server, browser):
    browser.find_element(By.ID, "tab-mission").click()
    wait = WebDriverWait(browser, 30)
    wait.until(lambda d: len(Select(d.find_element(By.ID, "mission-example")).options) >= 5)
    assert Select(browser.find_element(By.ID, "mission-example")).first_selected_option.text == "quadcopter_1p5kg"
    browser.find_element(By.ID, "mission-load").click()
    wait.until(lambda d: "quadcopter" in d.find_element(By.ID, "mission-json").get_attribute("value"))
    # The form shows the mission's values; a change there is written into the JSON.
    mass = browser.find_element(By.CSS_SELECTOR, "#mission-form-fields fieldset input")
    assert mass.get_attribute("value") == "0.75"
    mass.clear()
    mass.send_keys("0.8\t")
    assert json.loads(browser.find_element(By.ID, "mission-json").get_attribute("value"))["vehicle"]["mass_kg"] == 0.8
    mass.clear()
    mass.send_keys("0.75\t")
    assert json.loads(browser.find_element(By.ID, "mission-json").get_attribute("value"))["vehicle"]["mass_kg"] == 0.75
    t0 = time.monotonic()
    browser.find_element(By.ID, "mission-run").click()
    wait = WebDriverWait(browser, 120, poll_frequency=0.02)
    wait.until(lambda d: len(d.find_elements(By.CSS_SELECTOR, "#mission-table tbody tr")) == 3)
    print(f"quadcopter example optimized in the page in {time.monotonic() - t0:.2f} s (the page's own clock: "
          f"{browser.find_element(By.TAG_NAME, 'body').get_attribute('data-optimize-ms')} ms from the click to the table)")
    cli = cli_json("optimize", os.path.join(ROOT, "examples", "missions", "quadcopter_1p5kg.json"), "--top", "3")
    pick = cli["results"][0]
    first = browser.find_element(By.CSS_SELECTOR, "#mission-table tbody tr").text
    for key in ("motor", "esc", "prop", "battery"):
        assert pick[key] in first, (key, pick[key], first)
    assert f"{pick['objective'] / 60:.2f} min" in first
    screenshot(browser, "mission_optimizer.png")


def test_calibration(server, browser):
    browser.find_element(By.ID, "tab-calibrate").click()
    log = os.path.abspath(os.path.join(ROOT, "examples", "dyno_log.csv"))
    browser.find_element(By.ID, "cal-files").send_keys(log)
    browser.find_element(By.ID, "cal-run").click()
    wait = WebDriverWait(browser, 60)
    wait.until(EC.presence_of_element_located((By.ID, "cal-params")))
    cli = cli_json("calibrate", log, "--motor-id", "my_motor", "--esc-id", "my_esc")
    assert browser.find_element(By.ID, "cal-status").text == f"calibrate: {cli['summary']}"
    params = browser.find_element(By.ID, "cal-params").text
    assert f"{cli['motor']['rm_ohm']:.6g}" in params
    screenshot(browser, "calibration.png")


def test_diagnosis(server, browser):
    """Diagnose in the page: the named causes and what the extended model still misses, as the CLI
    gives them."""
    browser.get(server)
    WebDriverWait(browser, 30).until(EC.element_to_be_clickable((By.ID, "tab-calibrate"))).click()
    log = os.path.abspath(os.path.join(ROOT, "examples", "dyno_log.csv"))
    files = browser.find_element(By.ID, "cal-files")
    files.clear()
    files.send_keys(log)
    browser.find_element(By.ID, "diag-run").click()
    WebDriverWait(browser, 60).until(EC.presence_of_element_located((By.ID, "diag-findings")))
    cli = cli_json("diagnose", log)
    assert browser.find_element(By.ID, "cal-status").text == f"diagnose: {cli['summary']}"
    shown = browser.find_element(By.ID, "diag-findings").text
    for f in cli["findings"]:
        assert f["cause"] in shown, (f["cause"], shown)
    for t in cli["remaining_trends"]:
        assert t["text"] in shown, (t["text"], shown)
    screenshot(browser, "diagnosis.png")


def test_optimize_cancel(server, browser):
    """A search that outlasts any wait (the eVTOL example with both groups, the capacity and the
    cruise speed free: tests/cli_runner.h LongSearchMission): the progress shows, Cancel stops it
    with the best so far."""
    with open(os.path.join(ROOT, "examples", "missions", "evtol_lift_cruise.json")) as f:
        m = json.load(f)
    for group in m["propulsion"].values():
        for part in ("motor", "esc", "prop"):
            group.pop(part, None)
    m["battery"]["capacity_ah"] = [2, 8]
    for s in m["segments"]:
        if s["type"] == "cruise":
            s["airspeed_m_s"] = [14, 24]
    browser.find_element(By.ID, "tab-mission").click()
    browser.execute_script("document.getElementById('mission-json').value = arguments[0];", json.dumps(m))
    browser.find_element(By.ID, "mission-time").clear()
    browser.find_element(By.ID, "mission-run").click()
    wait = WebDriverWait(browser, 30)
    wait.until(EC.text_to_be_present_in_element((By.ID, "mission-status"), "optimizing..."))
    wait.until(lambda d: d.find_element(By.ID, "mission-cancel").is_enabled())
    time.sleep(1.0)
    browser.find_element(By.ID, "mission-cancel").click()
    wait.until(EC.text_to_be_present_in_element((By.ID, "mission-status"), "(stopped: the best found so far)"))
    assert browser.find_element(By.ID, "mission-run").is_enabled()
