"""The documentation site as a person opens it: built here from docs/
(Sphinx, -W, the gallery not executed: its pages are checked by the
full build CI makes after the tests), then the front page, the tutorial
and two explanation pages opened in headless Chromium (Debian's
package): every image on them loaded, every link to the site's own
pages and anchors present."""

from __future__ import annotations

import html.parser
import json
import shutil
import subprocess
import sys
import urllib.parse
from pathlib import Path

import pytest
from browser import chromium, headless

ROOT = Path(__file__).resolve().parents[2]
#: The pages a new reader meets first: the index, the tutorial, the
#: how-to with the thesis's figures, and two explanation pages (the model
#: and contact dynamics).
PAGES = ("index.html", "tutorial.html", "studies.html", "model.html",
         "chatter.html")
#: Appended to a copy of a page: once it has loaded, the page's own
#: root element says how many images it has and which did not load.
PROBE = ("<script>window.addEventListener('load', function () {"
         "var bad = []; for (var i of document.images) {"
         "if (!i.complete || i.naturalWidth === 0) "
         "bad.push(i.getAttribute('src')); }"
         "var root = document.documentElement;"
         "root.setAttribute('data-images', String(document.images.length));"
         "root.setAttribute('data-broken', JSON.stringify(bad)); });"
         "</script></body>")


@pytest.fixture(scope="module")
def site(tmp_path_factory) -> Path:
    pytest.importorskip("sphinx")
    pytest.importorskip("myst_parser")
    out = tmp_path_factory.mktemp("site")
    done = subprocess.run(
        [sys.executable, "-m", "sphinx", "-q", "-W", "-b", "html",
         "-D", "plot_gallery=0", "-d", str(out / ".doctrees"),
         str(ROOT / "docs"), str(out / "html")],
        capture_output=True, text=True, timeout=900)
    assert done.returncode == 0, done.stderr[-3000:]
    return out / "html"


class _Targets(html.parser.HTMLParser):
    """The ids a page defines, and the links and images it has."""

    def __init__(self):
        super().__init__()
        self.ids, self.links, self.images = set(), [], []

    def handle_starttag(self, tag, attrs):
        attrs = dict(attrs)
        if attrs.get("id"):
            self.ids.add(attrs["id"])
        if tag == "a" and attrs.get("href"):
            self.links.append(attrs["href"])
        if tag == "img" and attrs.get("src"):
            self.images.append(attrs["src"])


def _parse(path: Path) -> _Targets:
    parser = _Targets()
    parser.feed(path.read_text(encoding="utf-8"))
    return parser


def _local(link: str) -> bool:
    scheme = urllib.parse.urlsplit(link).scheme
    return scheme in ("", "file") and not link.startswith("mailto:")


@pytest.mark.parametrize("name", PAGES)
def test_every_local_link_and_anchor_of_the_page_exists(site, name):
    page = site / name
    parsed = _parse(page)
    assert parsed.links, name
    missing = []
    for link in parsed.links:
        if not _local(link):
            continue
        parts = urllib.parse.urlsplit(link)
        target = (page.parent / urllib.parse.unquote(parts.path)).resolve() \
            if parts.path else page
        if not target.exists():
            missing.append(link)
        elif parts.fragment and target.suffix == ".html" and \
                parts.fragment not in _parse(target).ids:
            missing.append(link)
    for source in parsed.images:
        if _local(source) and not (page.parent / source).exists():
            missing.append(source)
    assert not missing, (name, missing[:10])


@pytest.mark.skipif(chromium() is None, reason="needs Chromium (CI "
                    "installs Debian's chromium)")
@pytest.mark.parametrize("name", PAGES)
def test_the_page_opens_in_a_browser_with_every_image(site, name,
                                                     tmp_path):
    page = site / name
    parsed = _opened(page, tmp_path / "profile")
    assert json.loads(parsed.broken) == [], name
    expected = len(_parse(page).images)
    assert int(parsed.images) == expected, name


class _Attributes(html.parser.HTMLParser):
    """The probe's two attributes on the dumped page's root element."""

    def __init__(self):
        super().__init__()
        self.images = self.broken = None

    def handle_starttag(self, tag, attrs):
        if tag == "html":
            attrs = dict(attrs)
            self.images = attrs.get("data-images")
            self.broken = attrs.get("data-broken")


def _opened(page: Path, profile: Path) -> "_Attributes":
    """A copy of ``page`` with the probe, opened in Chromium: the
    probe's attributes on the page as the browser left it."""
    text = page.read_text(encoding="utf-8")
    assert "</body>" in text
    probe = page.with_name(f"_probe_{page.name}")
    probe.write_text(text.replace("</body>", PROBE, 1), encoding="utf-8")
    dom = subprocess.run(
        [*headless(profile), "--virtual-time-budget=10000", "--dump-dom",
         probe.as_uri()],
        capture_output=True, text=True, timeout=120).stdout
    parsed = _Attributes()
    parsed.feed(dom)
    assert parsed.images is not None, (page.name, dom[:300])
    return parsed


def test_a_missing_image_is_seen(site, tmp_path):
    """The probe can fail: the same check on a copy of a page whose
    image file is gone names it."""
    if chromium() is None:
        pytest.skip("needs Chromium")
    name = next(n for n in PAGES if _parse(site / n).images)
    copy = tmp_path / "html"
    shutil.copytree(site, copy)
    image = _parse(copy / name).images[0]
    (copy / image).unlink()
    assert image in json.loads(_opened(copy / name,
                                       tmp_path / "profile").broken)
    with pytest.raises(AssertionError):
        test_every_local_link_and_anchor_of_the_page_exists(copy, name)
