"""The built site in a real browser: headless Chromium (Debian's chromium + chromium-driver).

The home page, the API index and one user-guide page must render: a screenshot that is not blank,
the page title, the search box, and no broken image.  The screenshots go to
``$BILD_MDO_DOCS_SCREENSHOTS`` if set, else next to the built site (a temporary folder).
"""
import os
import pathlib
import shutil

import pytest

CHROMIUM = shutil.which("chromium") or "/usr/bin/chromium"
CHROMEDRIVER = shutil.which("chromedriver") or "/usr/bin/chromedriver"
PAGES = {"home": "index.html", "api_index": "api/index.html", "user_guide_design": "user-guide/design.html"}


@pytest.fixture(scope="module")
def browser():
    if not (pathlib.Path(CHROMIUM).exists() and pathlib.Path(CHROMEDRIVER).exists()):
        pytest.fail("headless Chromium is needed: apt-get install chromium chromium-driver (make system does)")
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    options = webdriver.ChromeOptions()
    options.binary_location = CHROMIUM
    for arg in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
                "--window-size=1280,1000", "--hide-scrollbars"):
        options.add_argument(arg)
    driver = webdriver.Chrome(service=Service(CHROMEDRIVER), options=options)
    yield driver
    driver.quit()


def _load_all_images(driver):
    # Images below the fold may be lazy: load them all, then wait until each has finished.
    driver.execute_script("for (const i of document.images) { i.loading = 'eager'; i.src = i.src; }")
    driver.execute_async_script("""
        const done = arguments[arguments.length - 1];
        Promise.all(Array.from(document.images).map(i => i.complete ? null :
            new Promise(r => { i.onload = i.onerror = r; }))).then(() => done());""")
    return driver.execute_script(
        "return Array.from(document.images).map(i => [i.getAttribute('src'), i.complete && i.naturalWidth > 0]);")


def _not_blank(png):
    from PIL import Image, ImageStat

    image = Image.open(png).convert("L")
    colours = Image.open(png).convert("RGB").getcolors(maxcolors=1 << 20)
    return ImageStat.Stat(image).stddev[0] > 10 and len(colours) > 50


@pytest.mark.parametrize("name", PAGES)
def test_page_renders_in_chromium(docs_site, browser, name):
    from selenium.webdriver.common.by import By

    html = docs_site[0]
    shots = pathlib.Path(os.environ.get("BILD_MDO_DOCS_SCREENSHOTS", html.parent / "screenshots"))
    shots.mkdir(parents=True, exist_ok=True)
    browser.get((html / PAGES[name]).as_uri())
    images = _load_all_images(browser)
    shot = shots / f"{name}.png"
    browser.save_screenshot(str(shot))
    print(f"screenshot: {shot}")

    assert "bild-mdo" in browser.title
    assert browser.find_elements(By.TAG_NAME, "h1")
    search = browser.find_elements(By.CSS_SELECTOR, "form.sidebar-search-container input[name='q']")
    assert search and search[0].is_displayed()
    broken = [src for src, ok in images if not ok]
    assert broken == [], f"broken images on {PAGES[name]}: {broken}"
    if name != "api_index":
        assert images, "the page shows its figures"
    assert _not_blank(shot), f"blank screenshot {shot}"
