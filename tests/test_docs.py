"""The documentation site: it builds (``-W``: a docstring warning fails), it is offline, every
gallery script ran and drew its figure, and its pages render in headless Chromium (screenshots
not blank, every gallery image loaded).

The build copies ``docs/``, ``examples/gallery/`` and the files the pages include (the changelog,
the model's description) into a temporary folder, so the source tree is not written to (the
package is imported from ``src/``). Without Sphinx (the
``docs`` extra) or Chromium the test skips with the reason, except under ``CI`` where both are
installed by ``.ci/run`` and a missing one fails. ``DRYFRICTION_DOCS_HTML=docs/_build/html``
checks a site built by ``make docs`` instead of building again (``.ci/run`` does so).
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from matplotlib.image import imread

ROOT = Path(__file__).resolve().parents[1]
# the guide: install, quickstart, tutorials, how-to, explanation, reference
GUIDE_PAGES = ("index.html", "install.html", "quickstart.html", "tutorials/index.html",
               "tutorials/lab-record.html", "tutorials/trap-friction.html",
               "tutorials/stick-slip.html", "tutorials/direct-effect.html", "howto/index.html",
               "howto/units.html", "howto/protocols.html", "howto/sweeps.html",
               "howto/record-formats.html", "explanation/index.html",
               "explanation/readings.html", "explanation/rsf.html", "cli.html",
               "performance.html", "quality.html", "layout.html")
GALLERY = sorted((ROOT / "examples" / "gallery").glob("plot_*.py"))
CHROMIUM_FLAGS = [
    "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
    "--disable-background-networking", "--disable-component-update", "--disable-sync",
    "--hide-scrollbars",
]
# a tag that makes the browser fetch something: a page that needs the network (a CDN script,
# a web font, MathJax) breaks offline
FETCHING = re.compile(
    r"<(?:script|img|iframe|source|link)\b[^>]*\b(?:src|href)\s*=\s*[\"']?(?:https?:)?//",
    re.IGNORECASE)


def _missing(what: str) -> None:
    if os.environ.get("CI"):
        pytest.fail(f"{what} is missing under CI (.ci/run installs it)")
    pytest.skip(f"{what} is not installed (CI installs it)")


def _chromium() -> str:
    for name in ("chromium", "chromium-browser", "google-chrome"):
        path = shutil.which(name)
        if path:
            return path
    _missing("chromium (apt-get install -y chromium)")
    raise AssertionError  # unreachable: _missing skips or fails


def test_docs_configuration_is_offline() -> None:
    conf = (ROOT / "docs" / "conf.py").read_text()
    extensions = re.search(r"^extensions = \[(.*?)\]", conf, re.S | re.M).group(1)
    assert "plainmath" in extensions
    assert "intersphinx" not in extensions and "mathjax" not in extensions
    assert 'html_math_renderer = "plainmath"' in conf
    assert GALLERY, "no gallery scripts"
    for script in GALLERY:  # sphinx-gallery needs a title in the docstring of each
        text = script.read_text()
        assert text.startswith('"""\n') and "\n===" in text.split('"""')[1], script.name


@pytest.fixture(scope="module")
def site(tmp_path_factory: pytest.TempPathFactory) -> Path:
    prebuilt = os.environ.get("DRYFRICTION_DOCS_HTML")
    if prebuilt:  # a copy: the probe page below must not land in the user's site
        assert (Path(prebuilt) / "index.html").is_file(), f"{prebuilt} holds no built site"
        dest = tmp_path_factory.mktemp("prebuilt") / "html"
        shutil.copytree(prebuilt, dest)
        return dest
    try:
        import myst_parser  # noqa: F401
        import sphinx  # noqa: F401
        import sphinx_gallery  # noqa: F401
    except ImportError as exc:
        _missing(f"the docs extra ({exc.name}; pip install -e '.[docs]')")
    tmp = tmp_path_factory.mktemp("site")
    shutil.copytree(ROOT / "docs", tmp / "docs",
                    ignore=shutil.ignore_patterns("_build", "generated", "auto_examples",
                                                  "__pycache__"))
    shutil.copytree(ROOT / "examples" / "gallery", tmp / "examples" / "gallery",
                    ignore=shutil.ignore_patterns("__pycache__"))
    # the files the pages include: the changelog and the model's description (shipped in
    # the package, so it lives under src/)
    shutil.copy(ROOT / "CHANGELOG.md", tmp / "CHANGELOG.md")
    (tmp / "src" / "dryfriction" / "docs").mkdir(parents=True)
    shutil.copy(ROOT / "src" / "dryfriction" / "docs" / "model.md",
                tmp / "src" / "dryfriction" / "docs" / "model.md")
    # document the code under test, from where it is (Numba's cache is kept per source path)
    path = os.pathsep.join(filter(None, [str(ROOT / "src"), os.environ.get("PYTHONPATH")]))
    env = {**os.environ, "MPLBACKEND": "Agg", "PYTHONPATH": path}
    r = subprocess.run(
        [sys.executable, "-m", "sphinx", "-q", "-W", "--keep-going", "-b", "html",
         "-d", str(tmp / "doctrees"), str(tmp / "docs"), str(tmp / "html")],
        capture_output=True, text=True, timeout=600, env=env)
    assert r.returncode == 0, f"the site does not build:\n{r.stdout[-3000:]}{r.stderr[-3000:]}"
    return tmp / "html"


def _pngs_of(page: Path) -> list[Path]:
    html = page.read_text()
    return [(page.parent / src).resolve()
            for src in re.findall(r"<img\b[^>]*\bsrc=\"([^\"]+)\"", html)]


@pytest.mark.slow
@pytest.mark.ci
def test_site_builds_offline_with_every_gallery_figure(site: Path) -> None:
    pages = list(site.rglob("*.html"))
    names = {p.relative_to(site).as_posix() for p in pages}
    assert set(GUIDE_PAGES) | {"api.html", "model.html", "changelog.html"} <= names, names
    tracker = re.compile(r"\bissues?\s+\d+", re.IGNORECASE)
    for page in pages:
        hit = FETCHING.search(page.read_text())
        assert hit is None, f"{page.relative_to(site)} fetches {hit.group(0)!r}"
        # a reader has no tracker: no page names one of its issues (the highlighted source
        # listings of _modules/ are the code itself)
        if "_modules" not in page.parts:
            ref = tracker.search(page.read_text())
            assert ref is None, f"{page.relative_to(site)} names {ref.group(0)!r}"
    # the API reference is generated from the docstrings, down to the functions
    static = (site / "generated" / "dryfriction.theory.static.html").read_text()
    assert 'id="dryfriction.theory.static.static_friction"' in static
    assert "eq. 27" in static
    # the spec, the guide's pages and the changelog are part of the site, not links out of it
    assert "Very strong pinning" in (site / "model.html").read_text()
    assert "The trap ensemble" in (site / "howto" / "protocols.html").read_text()
    assert "Model objects" in (site / "changelog.html").read_text()
    # the landing page leads to every part of the guide: to each page, or to the index of
    # the part that lists it
    index = (site / "index.html").read_text()
    for page in GUIDE_PAGES[1:]:
        part = page.split("/")[0]
        listed = f'href="{page}' in index or (
            "/" in page and f'href="{page.split("/", 1)[1]}' in (site / part / "index.html")
            .read_text() and f'href="{part}/index.html' in index)
        assert listed, f"index.html does not lead to {page}"
    for script in GALLERY:
        page = site / "auto_examples" / f"{script.stem}.html"
        images = [p for p in _pngs_of(page) if "sphx_glr" in p.name]
        assert images, f"{script.name} drew no figure"
        for png in images:
            img = imread(png)  # raises on a file that is not a PNG
            assert img.shape[0] > 200 and np.std(img[..., :3]) > 0.02, png.name


def _screenshot(browser: str, page: Path, out: Path, profile: Path) -> np.ndarray:
    subprocess.run(
        [browser, *CHROMIUM_FLAGS, f"--user-data-dir={profile}", f"--screenshot={out}",
         "--window-size=1200,900", page.as_uri()],
        capture_output=True, timeout=120, check=False)
    assert out.is_file(), f"chromium wrote no screenshot of {page.name}"
    return imread(out)[..., :3]


@pytest.mark.slow
@pytest.mark.ci
def test_index_and_gallery_render_in_chromium(site: Path, tmp_path: Path) -> None:
    browser = _chromium()
    for name, page in (("index", site / "index.html"),
                       ("gallery", site / "auto_examples" / "index.html")):
        shot = _screenshot(browser, page, tmp_path / f"{name}.png", tmp_path / "profile")
        assert shot.shape[:2] == (900, 1200)
        # a blank or error page is one or two colours; text and figures give many
        assert np.std(shot) > 0.05, f"{name} screenshot is blank"
        colours = np.unique((shot * 255).astype(np.uint8).reshape(-1, 3), axis=0)
        assert len(colours) > 50, f"{name} screenshot has {len(colours)} colours"
    # every image of the gallery page loaded in the browser (naturalWidth > 0), counted after
    # the load event by a script added to a copy of the page beside it
    gallery = site / "auto_examples" / "index.html"
    probe = gallery.with_name("_probe.html")
    script = ("<script>window.addEventListener('load',function(){var im=document.images,ok=0;"
              "for(var i=0;i<im.length;i++){if(im[i].complete&&im[i].naturalWidth>0)ok++;}"
              "document.body.setAttribute('data-images',im.length+'/'+ok);});</script>")
    probe.write_text(gallery.read_text().replace("</body>", script + "</body>"))
    r = subprocess.run(
        [browser, *CHROMIUM_FLAGS, f"--user-data-dir={tmp_path / 'profile'}",
         "--virtual-time-budget=10000", "--dump-dom", probe.as_uri()],
        capture_output=True, text=True, timeout=120, check=False)
    found = re.search(r'data-images="(\d+)/(\d+)"', r.stdout)
    assert found, f"the probe did not run: {r.stderr[-500:]}"
    total, loaded = map(int, found.groups())
    assert total >= len(GALLERY) and loaded == total, f"{loaded} of {total} images loaded"
    probe.unlink()


# pages with the widest code and tables
NARROW_PAGES = ("index.html", "quickstart.html", "cli.html", "tutorials/lab-record.html",
                "tutorials/direct-effect.html", "howto/sweeps.html", "performance.html",
                "explanation/interface.html", "auto_examples/plot_command_line.html",
                "auto_examples/plot_lab_record_fit.html")
OVERFLOW_PROBE = (
    "<script>window.addEventListener('load',function(){var w=window.innerWidth,bad=[];"
    "if(document.documentElement.scrollWidth>w+1)bad.push('page:'+document.documentElement"
    ".scrollWidth);var pre=document.querySelectorAll('pre');for(var i=0;i<pre.length;i++){"
    "if(pre[i].scrollWidth>pre[i].clientWidth+1)bad.push('pre'+i+':'+pre[i].scrollWidth+'>'"
    "+pre[i].clientWidth);}document.body.setAttribute('data-overflow',w+'|'+pre.length+'|'"
    "+bad.join(','));});</script>")


@pytest.mark.slow
@pytest.mark.ci
def test_pages_fit_an_800px_window_in_chromium(site: Path, tmp_path: Path) -> None:
    """At 800 px no page is wider than the window and no code block is cut: long lines wrap
    (docs/_static/custom.css), wide tables scroll inside their own box."""
    browser = _chromium()
    for name in NARROW_PAGES:
        page = site / name
        probe = page.with_name("_probe_" + page.name)
        probe.write_text(page.read_text().replace("</body>", OVERFLOW_PROBE + "</body>"))
        try:
            r = subprocess.run(
                [browser, *CHROMIUM_FLAGS, f"--user-data-dir={tmp_path / 'profile'}",
                 "--window-size=800,900", "--virtual-time-budget=10000", "--dump-dom",
                 probe.as_uri()],
                capture_output=True, text=True, timeout=120, check=False)
        finally:
            probe.unlink()
        found = re.search(r'data-overflow="(\d+)\|(\d+)\|([^"]*)"', r.stdout)
        assert found, f"the probe did not run on {name}: {r.stderr[-500:]}"
        width, blocks, bad = found.groups()
        assert int(width) <= 800, f"{name}: window {width} px"
        assert bad == "", f"{name} at {width} px ({blocks} code blocks): {bad}"
