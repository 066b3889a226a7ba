"""In headless Chromium: each new answer of the Net tab replaces the last (issue #44, item 4), and the net that
fits a sheet is named by its sheet, not by a seed (item 3)."""

from __future__ import annotations

import pytest

from .test_browser import open_page, slim_column, wait
from .test_browser_net import by_id, type_into

pytestmark = pytest.mark.slow


def _ways(browser) -> list:
    return browser.find_elements("css selector", '[data-testid="net-ways-out"] button')


def _a_yes_on_a3(browser, server) -> None:
    from selenium.webdriver.support.ui import Select

    open_page(browser, server)
    slim_column(browser)
    by_id(browser, "tab-net").click()
    Select(by_id(browser, "net-sheet")).select_by_value("A3")
    Select(by_id(browser, "net-pieces")).select_by_value("one")
    type_into(browser, "net-face-size", "10")
    type_into(browser, "net-timeout", "5")
    type_into(browser, "net-count", "1")
    # "does one piece fit?": yes, and the net found is open, named by its sheet (it has no seed worth naming)
    by_id(browser, "net-fits").click()
    answer = wait(browser, lambda d: by_id(d, "net-fits-answer").get_attribute("data-answer"), timeout=120,
                  what="the answer")
    assert answer == "yes", by_id(browser, "net-fits-answer").text


def test_the_net_that_fits_is_named_by_its_sheet(server, browser):
    _a_yes_on_a3(browser, server)
    chosen = wait(browser, lambda d: d.find_element("id", "net-chosen-label").text, what="the chosen net")
    assert "seed" not in chosen and "A3" in chosen, chosen


def test_a_new_answer_replaces_the_last_one(server, browser):
    from selenium.webdriver.support.ui import Select

    _a_yes_on_a3(browser, server)
    # a gallery on a sheet the net does not fit: its refusal and ways out, and the old "yes" is gone
    Select(by_id(browser, "net-sheet")).select_by_value("A5")
    type_into(browser, "net-face-size", "20")
    by_id(browser, "net-generate").click()
    buttons = wait(browser, _ways, timeout=120, what="the ways out")
    assert buttons
    assert by_id(browser, "net-fits-answer").get_attribute("data-answer") is None
    assert by_id(browser, "net-fits-answer").text == ""
    # a new question: the ways out of the last answer go at once, the new answer stands alone
    by_id(browser, "net-fits").click()
    assert not _ways(browser)
    wait(browser, lambda d: by_id(d, "net-fits-answer").get_attribute("data-answer"), timeout=120,
         what="the second answer")
    assert not _ways(browser)


def test_the_maker_forms_show_plain_labels_not_keys(server, browser):
    from selenium.webdriver.support.ui import Select

    open_page(browser, server)
    maker = Select(browser.find_element("id", "maker"))
    for name, key, words in (("revolution", "curve_threshold", "curve grey level"),
                             ("tube", "profile_open", "open profile (a ribbon)")):
        maker.select_by_value(name)
        wait(browser, lambda d, n=name: d.find_element("id", "maker-form").get_attribute("data-maker") == n,
             what="the form")
        form = browser.find_element("id", "maker-form")
        label = form.find_element("css selector", f'[data-testid="param-{key}"]')
        assert label.text.strip() == words, label.text
        texts = [e.text for e in form.find_elements("css selector", "label")]
        assert texts and not any("_" in t for t in texts), texts
