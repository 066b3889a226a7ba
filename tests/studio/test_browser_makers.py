"""Every maker of the makers table in the page, its keys in a form generated from its row (headless Chromium)."""

from __future__ import annotations

import json
import urllib.request

import pytest

from ._helpers import SHOTS
from .test_browser import attr, open_page, wait

pytestmark = pytest.mark.slow


def _extents(driver) -> str:
    return driver.find_element("id", "volume").text.split("·")[-1].strip()


def test_the_implicit_maker_from_the_select_and_its_generated_size_field(server, browser):
    from selenium.webdriver.common.keys import Keys
    from selenium.webdriver.support.ui import Select

    with urllib.request.urlopen(server["url"] + "/api/info", timeout=10) as r:
        table = json.loads(r.read())["makers"]
    open_page(browser, server)
    maker = Select(browser.find_element("id", "maker"))
    assert [o.get_attribute("value") for o in maker.options] == [m["name"] for m in table]
    # the drawn tube: its own radius field, the rest of its keys generated (cap's words as a select)
    maker.select_by_value("tube")
    wait(browser, lambda d: d.find_element("id", "maker-form").get_attribute("data-maker") == "tube", what="the form")
    form = browser.find_element("id", "maker-form")
    assert not form.find_elements("css selector", '[data-param="radius"]')
    cap = form.find_element("css selector", 'select[data-param="cap"]')
    assert [o.get_attribute("value") for o in cap.find_elements("tag name", "option")] == ["flat", "round"]

    maker.select_by_value("implicit")
    wait(browser, lambda d: _extents(d) == "25×25×25" and attr(d, "wf", "data-well-formed") == "true",
         what="the ball on the whole grid")
    before = int(attr(browser, "volume", "data-volume"))
    size = browser.find_element("css selector", '#maker-form input[data-param="size"]')
    implicit = {p["name"]: p for p in next(m for m in table if m["name"] == "implicit")["params"]}
    assert (size.get_attribute("min"), size.get_attribute("max"), size.get_attribute("value")) == ("2", "256", "25")
    label = size.find_element("xpath", "..")
    assert label.text.strip() == "size" and implicit["size"]["help"] in label.get_attribute("title")
    assert browser.find_element("id", "maker-implicit").is_displayed()
    assert not browser.find_element("id", "maker-revolution").is_displayed()
    size.send_keys(Keys.CONTROL, "a")
    size.send_keys("15", Keys.TAB)
    wait(browser, lambda d: _extents(d) == "15×15×15", what="the ball on a 15 grid")
    assert int(attr(browser, "volume", "data-volume")) < before / 3  # (15 / 25)³ of it, about
    # out of the row's range: the row's words on the page, and no shape
    size.send_keys(Keys.CONTROL, "a")
    size.send_keys("1", Keys.TAB)
    wait(browser, lambda d: "shape.size: expected an integer in 2..256, got 1" in d.find_element("id", "message").text,
         what="the refusal")
    assert browser.find_element("id", "wf").text == "no shape"
    browser.save_screenshot(str(SHOTS / "maker-form.png"))
