"""Figures are big enough to read: PNGs at 150 dpi (a panel is 840 px wide, for a slide), and
``report.html`` read in a window 800 px wide shows the figures' 10-point text at 11 px or more
(two panels side by side shrank to 10 px: the report shows them one under the other)."""

from __future__ import annotations

import base64
import io
import re
import shutil
import subprocess
from pathlib import Path

import pytest
from matplotlib.figure import Figure
from PIL import Image

from dryfriction.plots import report
from dryfriction.plots.style import DPI, PANEL, new_figure, save_figure, save_png

WINDOW = 800
COLUMN = WINDOW - 2 * 8 - 2
"""The width an image gets in report.html at 800 px: the body's padding (.5 em a side under
900 px) and the image's border (1 px a side) taken off."""
TEXT_PT = 10.0
"""Tick labels and axis labels of every figure (matplotlib's default font size, points)."""
SMALLEST_PX = 11.0


def _png_size(raw: bytes) -> tuple[int, float]:
    """Width in pixels and resolution (dots per inch, from the pHYs chunk) of a PNG."""
    img = Image.open(io.BytesIO(raw))
    return img.size[0], float(img.info["dpi"][0])


def _shown_text_px(width_px: float, dpi: float, shown_px: float) -> float:
    """How many CSS pixels 10-point text of an image ``width_px`` wide at ``dpi`` takes when the
    page shows the image ``shown_px`` wide."""
    return TEXT_PT / 72.0 * dpi * shown_px / width_px


def test_a_panel_png_is_150_dpi_and_wide_enough_for_a_slide():
    buf = io.BytesIO()
    fig, _ = new_figure()
    save_png(fig, buf)
    width, dpi = _png_size(buf.getvalue())
    assert DPI == 150 and round(dpi) == 150
    assert width == round(PANEL[0] * 150) >= 800
    buf = io.BytesIO()
    save_figure(fig, buf)  # the command line's writer: the same default
    assert _png_size(buf.getvalue()) == (width, pytest.approx(dpi))


def test_panel_pngs_cut_a_row_of_panels_and_leave_one_panel_whole():
    fig = report._fig1()
    buf = io.BytesIO()
    save_png(fig, buf)
    whole, _ = _png_size(buf.getvalue())
    a, b = report.panel_pngs(fig, buf.getvalue(), "fig1.png")
    assert (a[0], b[0]) == ("fig1.png (a)", "fig1.png (b)")
    wa, wb = _png_size(a[2])[0], _png_size(b[2])[0]
    assert wa + wb == whole and abs(wa - wb) < 0.1 * whole
    one, _ = new_figure()
    assert report.panel_pngs(one, None, "fig3.png") == ()
    stacked, _ = new_figure((PANEL[0], 2 * PANEL[1]), 2, 1)
    assert report.panel_pngs(stacked, None, "x.png") == ()


def _embedded(page: str) -> dict[str, bytes]:
    return {alt: base64.b64decode(data) for alt, data in
            re.findall(r'<img alt="([^"]+)" src="data:image/png;base64,([^"]+)"', page)}


@pytest.fixture(scope="module")
def page(tmp_path_factory: pytest.TempPathFactory) -> str:
    """report.html with every figure drawn as ``reproduce`` draws it (serially)."""
    tmp = tmp_path_factory.mktemp("report")
    drawn = [report._draw((i, tmp, "png", None)) for i in range(len(report._plots()))]
    return report.report_html(tmp, report.compute_summary(),
                              images={n: im for n, im, _ in drawn},
                              panels={n: p for n, _, p in drawn if p})


@pytest.mark.slow
def test_report_text_is_readable_in_a_window_800_px_wide(page):
    images = _embedded(page)
    assert len(images) >= len(report.FIGURE_FILES) + len(report.EXTRA_FILES)
    for alt, raw in images.items():
        width, dpi = _png_size(raw)
        shown = min(width, COLUMN)  # max-width: 100 %, never wider than the image
        px = _shown_text_px(width, dpi, shown)
        assert px >= SMALLEST_PX, f"{alt}: 10-point text shown {px:.1f} px high at 800 px"
    css = re.search(r"<style>(.*?)</style>", page, re.S).group(1)
    assert re.search(r"figure img\{[^}]*max-width:100%", css)
    assert re.search(r"@media \(max-width:900px\)\{body\{[^}]*padding:0 \.5em", css)


@pytest.mark.slow
@pytest.mark.ci
def test_report_text_is_readable_in_chromium_at_800_px(page, tmp_path: Path):
    browser = next((shutil.which(n) for n in ("chromium", "chromium-browser", "google-chrome")
                    if shutil.which(n)), None)
    if browser is None:
        pytest.skip("chromium is not installed")
    probe = tmp_path / "report.html"
    script = ("<script>window.addEventListener('load',function(){var im=document.images,s=[];"
              "for(var i=0;i<im.length;i++){s.push(im[i].alt+'|'+im[i].clientWidth+'|'"
              "+im[i].naturalWidth);}document.body.setAttribute('data-shown',s.join(';'));"
              "});</script>")
    probe.write_text(page.replace("</body>", script + "</body>"))
    r = subprocess.run(
        [browser, "--headless", "--no-sandbox", "--disable-gpu", "--hide-scrollbars",
         f"--user-data-dir={tmp_path / 'profile'}", f"--window-size={WINDOW},900",
         "--virtual-time-budget=10000", "--dump-dom", probe.as_uri()],
        capture_output=True, text=True, timeout=120, check=False)
    found = re.search(r'data-shown="([^"]*)"', r.stdout)
    assert found, f"the probe did not run: {r.stderr[-500:]}"
    dpi = {alt: _png_size(raw)[1] for alt, raw in _embedded(page).items()}
    shown = [s.split("|") for s in found.group(1).split(";")]
    assert len(shown) == len(dpi)
    for alt, client, natural in shown:
        px = _shown_text_px(float(natural), dpi[alt], float(client))
        assert px >= SMALLEST_PX, f"{alt}: 10-point text shown {px:.1f} px high"


def test_the_check_sees_a_two_panel_figure_shrunk():
    # the old report: fig1.png whole, 11.2 in wide, in a 782 px column
    fig: Figure = report._fig1()
    buf = io.BytesIO()
    save_png(fig, buf)
    width, dpi = _png_size(buf.getvalue())
    assert _shown_text_px(width, dpi, min(width, COLUMN)) < SMALLEST_PX
