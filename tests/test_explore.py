"""The explorer without a browser: its requests (``eccjump.explorer.api``), the local server,
the command ``eccjump explore`` and the widget's Python side (``eccjump.explore``).

The page itself is tested in a real browser by tests/test_explorer_browser.py."""

from __future__ import annotations

import json
import math
import re
import select
import signal
import socket
import subprocess
import sys
import threading
import time
import urllib.error
import urllib.request
from pathlib import Path

import numpy as np
import pytest
from fuzz_cases import http_exchange
from reference_points import SLIP_FIRST, SLIP_FIRST_KW

import eccjump
from eccjump.explorer import api, controls, server
from eccjump.explorer.server import ExplorerServer

#: The README's worked example (it jumps straight out of rolling) and the paper's Fig. 3b
#: body on a 30° ramp (it slips first), in the sliders' units.
README = {"alpha": "40", "chi": "0.15", "km": "0.02", "mu_s": "1"}
FIG3B = {"alpha": "30", "chi": "0.5", "km": "0.4", "mu_s": "1", "t_max": "9"}


def ok(endpoint: str, query: dict[str, str]) -> dict:
    status, body = api.handle(endpoint, query)
    assert status == 200, body
    json.dumps(body, allow_nan=False)  # what the server sends
    return body


def refused(endpoint: str, query: dict[str, str]) -> str:
    status, body = api.handle(endpoint, query)
    assert status == 400, body
    assert set(body) == {"error"} and len(body["error"]) <= 200
    assert "Traceback" not in body["error"]
    return body["error"]


# --- the controls --------------------------------------------------------------------------


def test_every_slider_starts_inside_its_range_on_a_step():
    for c in controls.CONTROLS:
        assert c.lo <= c.default <= c.hi, c
        steps = (c.default - c.lo) / c.step
        assert steps == pytest.approx(round(steps), abs=1e-9), c
    spec = ok("controls", {})
    assert [c["key"] for c in spec["controls"]] == [c.key for c in controls.CONTROLS]
    assert spec["rules"] == ["paper", "normal_force"]
    assert set(spec["reasons"]) == {r.name for r in eccjump.Reason}


def test_the_docs_table_is_the_controls_table():
    doc = (Path(__file__).parents[1] / "docs" / "explorer.md").read_text()
    rows = {
        key: tuple(cell.strip() for cell in cells)
        for key, *cells in re.findall(
            r"^\| `(\w+)` \| [^|]+ \| ([^|]*) \| ([^|]*) \| ([^|]*) \|$", doc, re.M
        )
    }
    assert set(rows) == {c.key for c in controls.CONTROLS} and "| `rule` |" in doc
    for c in controls.CONTROLS:
        shown = (f"{c.lo:g} … {c.hi:g}".replace("-", "−"), f"{c.step:g}", f"{c.default:g}")
        assert rows[c.key] == shown, c.key


# --- the region slice ----------------------------------------------------------------------


def test_region_slice_is_the_classification_at_its_cell_centres():
    body = ok("region", {"km": "0.02", "mu_s": "1"})
    n = body["n"]
    codes = np.array(body["codes"]).reshape(n, n)  # rows: alpha, columns: chi
    chi, alpha = np.array(body["chi"]), np.radians(body["alpha_deg"])
    for j, i in [(0, 0), (26, 9), (40, 30), (n - 1, n - 1), (10, 50)]:
        expected = eccjump.jarm(alpha[j], chi[i], 0.02, 1.0).reason
        assert codes[j, i] == expected, (j, i)
    # the README's body (alpha 40 deg, chi 0.15) jumps: so does its cell
    j, i = int(40 / 90 * n), int(0.15 * n)
    assert body["names"][codes[j, i]] == "JARM"
    valid = codes != eccjump.Reason.INVALID_PARAMS
    assert body["jarm_fraction"] == pytest.approx((codes[valid] == 0).mean())
    assert sum(body["counts"].values()) == n * n


def test_region_slice_follows_km_mu_s_rule_and_start():
    base = ok("region", {"km": "0.02", "mu_s": "1"})["codes"]
    for change in ({"km": "0.1"}, {"mu_s": "0.3"}, {"rule": "normal_force"}, {"omega0": "1"}):
        assert ok("region", {"km": "0.02", "mu_s": "1", **change})["codes"] != base, change


def test_region_slice_marks_the_bodies_that_do_not_exist():
    body = ok("region", {"km": "0.5"})
    n = body["n"]
    codes = np.array(body["codes"]).reshape(n, n)
    chi = np.array(body["chi"])
    invalid = codes == eccjump.Reason.INVALID_PARAMS
    assert (invalid == (chi > 0.5)[None, :]).all()


# --- the motion ----------------------------------------------------------------------------


def test_motion_numbers_of_the_readme_body():
    body = ok("motion", README)
    assert body["verdict"]["reason"] == "JARM" and body["verdict"]["is_jarm"]
    assert body["verdict"]["theta_J_deg"] == pytest.approx(334.3438379, abs=1e-6)
    lift = body["numbers"]["liftoff"]
    assert lift["theta_deg"] == pytest.approx(334.3438379, abs=1e-6)
    assert lift["t"] == pytest.approx(4.183023843, abs=1e-8)
    assert lift["from"] == "ROLL" and lift["reason"] == "liftoff"
    assert body["numbers"]["sequence"][:2] == ["ROLL", "FLIGHT"]


def test_motion_numbers_of_the_fig3b_body_are_the_readmes():
    body = ok("motion", FIG3B)
    n = body["numbers"]
    assert n["slip"]["theta_deg"] == pytest.approx(316.471677, abs=1e-5)
    assert n["slip"]["t"] == pytest.approx(5.26644580, abs=1e-7)
    assert n["liftoff"]["theta_deg"] == pytest.approx(325.174146, abs=1e-5)
    assert (n["liftoff"]["from"], n["liftoff"]["reason"]) == ("SLIP", "normal_force")
    assert n["flight"]["apex"] == pytest.approx(0.0749541, abs=1e-7)
    assert n["flight"]["distance"] == pytest.approx(3.49484, abs=1e-5)
    assert n["flight"]["t_landing"] == pytest.approx(7.09086859, abs=1e-7)
    assert (n["flights"], n["impacts"]) == (2, 1)
    assert body["verdict"]["reason"] in ("SLIP_BEFORE", "SLIP_AT_JUMP")
    assert body["status"] == "t_max" and body["t_end"] == pytest.approx(9.0)


def test_motion_samples_are_the_run_at_even_times():
    body = ok("motion", FIG3B)
    t = np.array(body["t"])
    assert t[0] == 0 and t[-1] == pytest.approx(body["t_end"], abs=1e-5)
    assert np.allclose(np.diff(t), t[-1] / (t.size - 1), atol=2e-5)
    res = eccjump.simulate(
        *SLIP_FIRST, mu_s=1.0, t_max=9.0, dense_output=True, max_transitions=api.MAX_TRANSITIONS
    )
    theta, _, along, _, b, _ = res.sol(t)
    assert np.allclose(body["theta"], theta, atol=1e-5)
    assert np.allclose(body["cx"], along, atol=1e-5) and np.allclose(body["cy"], b, atol=1e-5)
    # the centre of mass is chi from the axis, at the angle theta from the normal
    gx, gy = np.array(body["gx"]) - body["cx"], np.array(body["gy"]) - body["cy"]
    assert np.allclose(np.hypot(gx, gy), 0.5, atol=3e-5)
    assert np.allclose(np.arctan2(gx, gy), np.arctan2(np.sin(theta), np.cos(theta)), atol=1e-4)
    # each sample's mode is its segment's; the axis is on the ramp except in flight
    modes = [body["modes"][m] for m in body["mode"]]
    for s in body["segments"]:
        inside = (t > s["t_start"] + 1e-9) & (t < s["t_end"] - 1e-9)
        assert {modes[k] for k in np.flatnonzero(inside)} <= {s["mode"]}
    contact = np.array([m != "FLIGHT" for m in modes])
    assert np.allclose(np.array(body["cy"])[contact], 1.0, atol=1e-5)
    assert (np.array(body["cy"])[~contact] >= 1.0 - 1e-5).all() and (~contact).any()


def test_motion_of_a_body_that_does_not_exist_is_a_message():
    message = refused("motion", {"chi": "0.5", "km": "0.6"})
    assert message.startswith("No such body") and "1 − χ = 0.5" in message


@pytest.mark.parametrize(
    ("query", "names"),
    [
        ({"km": "0"}, "km"),
        ({"alpha": "abc"}, "alpha"),
        ({"alpha": "91"}, "alpha"),
        ({"theta0": "nan"}, "theta0"),
        ({"mu_s": "-1"}, "mu_s"),
        ({"mu_s": "0.5", "mu_k": "1", "tie": "0"}, "mu_k"),
        ({"rule": "bogus"}, "rule"),
        ({"t_max": "1e9"}, "t_max"),
    ],
)
def test_bad_queries_are_short_messages_naming_the_parameter(query, names):
    assert re.search(rf"\b{names}\b", refused("motion", query))


def test_mu_k_follows_mu_s_when_tied():
    tied = ok("motion", {**FIG3B, "mu_k": "0.2", "tie": "1"})
    free = ok("motion", {**FIG3B, "mu_k": "0.2", "tie": "0"})
    assert tied["params"]["mu_k"] == 1.0 and free["params"]["mu_k"] == 0.2
    assert tied["numbers"] != free["numbers"]


def test_unknown_request_and_internal_errors_are_messages(monkeypatch, capsys):
    assert api.handle("nope", {})[0] == 404

    def broken(query):
        raise RuntimeError("boom")

    monkeypatch.setitem(api.ENDPOINTS, "motion", broken)
    status, body = api.handle("motion", {})
    assert status == 500 and "RuntimeError" in body["error"] and "boom" not in body["error"]
    assert "Traceback" in capsys.readouterr().err  # for whoever runs the server


# --- the server ----------------------------------------------------------------------------


def get(url: str) -> tuple[int, str, bytes]:
    try:
        with urllib.request.urlopen(url, timeout=30) as r:
            return r.status, r.headers["Content-Type"], r.read()
    except urllib.error.HTTPError as err:
        return err.code, err.headers["Content-Type"], err.read()


def test_server_serves_the_page_and_answers_requests():
    with ExplorerServer(0) as srv:
        assert re.fullmatch(r"http://127\.0\.0\.1:\d+/", srv.url) and srv.port > 0
        status, kind, page = get(srv.url)
        assert status == 200 and kind.startswith("text/html") and b"explorer.js" in page
        assert get(srv.url + "explorer.js")[1].startswith("text/javascript")
        assert get(srv.url + "explorer.css")[1].startswith("text/css")
        status, kind, data = get(srv.url + "api/motion?alpha=40&chi=0.15&km=0.02&mu_s=1")
        assert status == 200 and kind == "application/json"
        assert json.loads(data)["numbers"]["liftoff"]["theta_deg"] == pytest.approx(334.34383792)
        status, _, data = get(srv.url + "api/motion?chi=0.9&km=0.5")
        assert status == 400 and json.loads(data)["error"].startswith("No such body")
        assert get(srv.url + "secret.txt")[0] == 404
        assert get(srv.url + "../pyproject.toml")[0] == 404
    with pytest.raises(OSError):  # stopped: nothing listens any more
        get(srv.url)


# --- the P(JARM) panel of an uncertainty map ------------------------------------------------

#: A small uncertainty map's grid: χ given in descending order (the page draws it ascending).
U_ALPHA = np.radians([35.0, 40.0, 45.0])
U_CHI = np.array([0.2, 0.15, 0.1])
U_KM_FRAC = np.array([0.0, 0.1, 0.4])


@pytest.fixture(scope="module")
def umap():
    return eccjump.uncertainty_map(U_ALPHA, U_CHI, U_KM_FRAC, 1.0, sd={"alpha": 0.004}, n=100)


@pytest.fixture(scope="module")
def map_files(umap, tmp_path_factory):
    folder = tmp_path_factory.mktemp("maps")
    region = eccjump.region(U_ALPHA, U_CHI, U_KM_FRAC, 1.0)
    return umap.save(folder / "p.npz"), region.save(folder / "region.npz")


@pytest.mark.parametrize(
    ("chi", "km", "k"), [("0.15", "0.02", 0), ("0.2", "0.1", 1), ("0.5", "0.5", 2)]
)
def test_uncertainty_panel_is_the_maps_slice_nearest_to_km_over_1_minus_chi(umap, chi, km, k):
    status, body = api.handle("uncertainty", {"chi": chi, "km": km}, umap)
    assert status == 200 and body["available"]
    json.dumps(body, allow_nan=False)
    assert body["km_frac"] == U_KM_FRAC[k]
    assert body["wanted_km_frac"] == pytest.approx(float(km) / (1 - float(chi)))
    ascending = umap.fields["p_jarm"][:, ::-1, k]  # rows α, columns χ ascending
    assert body["p_jarm"] == pytest.approx(np.round(ascending, 4).ravel().tolist())
    assert np.all(np.array(body["p_jarm_low"]) <= np.array(body["p_jarm_high"]))
    assert body["chi_edges"] == pytest.approx([0.075, 0.125, 0.175, 0.225])
    assert body["alpha_edges"] == pytest.approx([32.5, 37.5, 42.5, 47.5])
    assert body["levels"] == [0.5, 0.95] and "alpha ± 0.229°" in body["tolerances"]


def test_uncertainty_panel_without_a_map_or_with_a_bad_query(umap):
    assert api.handle("uncertainty", {}) == (200, {"available": False})
    assert "km" in refused_with("uncertainty", {"km": "2"}, umap)


def refused_with(endpoint: str, query: dict[str, str], m: object) -> str:
    status, body = api.handle(endpoint, query, m)
    assert status == 400 and len(body["error"]) <= 200
    return body["error"]


def test_server_answers_the_uncertainty_panel_of_its_map_file(map_files, umap):
    with ExplorerServer(0, uncertainty=map_files[0]) as srv:
        status, _, data = get(srv.url + "api/uncertainty?chi=0.15&km=0.02")
    assert status == 200
    assert json.loads(data)["p_jarm"] == api.handle("uncertainty", {}, umap)[1]["p_jarm"]


def test_a_map_of_another_kind_is_refused_naming_it(map_files):
    with pytest.raises(ValueError, match=r"^uncertainty: .*region\.npz.* holds a 'jarm' map"):
        ExplorerServer(0, uncertainty=map_files[1])
    with pytest.raises(ValueError, match=r"^uncertainty is a 'jarm' map, not an uncertainty"):
        ExplorerServer(0, uncertainty=eccjump.load(map_files[1]))
    with pytest.raises(TypeError, match="uncertainty must be an UncertaintyMap"):
        ExplorerServer(0, uncertainty=3)  # type: ignore[arg-type]
    with pytest.raises(FileNotFoundError):
        ExplorerServer(0, uncertainty=map_files[1].with_name("none.npz"))


def test_cli_refuses_a_map_of_another_kind_in_one_line(map_files, capsys):
    from eccjump.cli import main

    assert main(["explore", "--no-browser", "--uncertainty", str(map_files[1])]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("eccjump: error: --uncertainty: ") and "holds a 'jarm' map" in err
    assert len(err.splitlines()) == 1 and len(err) <= 200
    assert (
        main(["explore", "--no-browser", "--uncertainty", str(map_files[1].with_name("none.npz"))])
        == 1
    )
    assert "--uncertainty" in capsys.readouterr().err


# --- the server under abuse (raw requests from this machine) -------------------------------

#: Every kind of route: the page's files, the requests, an unknown request, an unknown file.
ROUTES = (
    "/", "/index.html", "/explorer.js", "/explorer.css", "/api/controls", "/api/region",
    "/api/motion?alpha=40", "/api/nope", "/nope",
)  # fmt: skip


def raw_get(port: int, target: str = "/api/controls", *headers: str) -> bytes:
    """A GET of ``target`` with these header lines (Host: this server's by default)."""
    lines = headers or (f"Host: 127.0.0.1:{port}",)
    return "\r\n".join((f"GET {target} HTTP/1.1", *lines, "", "")).encode("latin-1")


@pytest.fixture(scope="module")
def srv():
    with ExplorerServer(0) as s:
        yield s


def answers(port: int) -> bool:
    return http_exchange(port, raw_get(port))[0] == 200


@pytest.mark.parametrize(
    "hosts",
    [
        ["evil.example"],
        ["evil.example:{port}"],
        ["127.0.0.1.evil.example:{port}"],
        ["127.0.0.1:1"],
        ["0.0.0.0:{port}"],
        [],
        ["127.0.0.1:{port}", "evil.example"],
    ],
)
def test_another_host_is_refused_before_any_route(srv, hosts):
    """A page of another site whose name was rebound to 127.0.0.1 sends its own name as Host:
    403 on every route, and for any method, before the route runs."""
    headers = [f"Host: {h.format(port=srv.port)}" for h in hosts]
    for target in ROUTES:
        status, body = http_exchange(srv.port, raw_get(srv.port, target, *headers, "X: 1"))
        assert status == 403 and f"127.0.0.1:{srv.port}".encode() in body, (target, body)
        assert len(body) < 200
    post = "\r\n".join(("POST /api/motion HTTP/1.1", *headers, "", "")).encode()
    assert http_exchange(srv.port, post)[0] == 403  # not 501: no method runs either


@pytest.mark.parametrize("host", ["127.0.0.1:{port}", "localhost:{port}", "[::1]:{port}",
                                  "LOCALHOST:{port}", "127.0.0.1", "localhost"])  # fmt: skip
def test_this_machines_names_are_served(srv, host):
    request = raw_get(srv.port, "/", f"Host: {host.format(port=srv.port)}")
    assert http_exchange(srv.port, request)[0] == 200


def test_another_sites_origin_is_refused(srv):
    host = f"Host: 127.0.0.1:{srv.port}"
    for origin in ("http://evil.example", "null", f"https://127.0.0.1:{srv.port}"):
        status, body = http_exchange(srv.port, raw_get(srv.port, "/", host, f"Origin: {origin}"))
        assert status == 403 and b"Origin" in body, origin
    own = raw_get(srv.port, "/api/controls", host, f"Origin: http://127.0.0.1:{srv.port}")
    assert http_exchange(srv.port, own)[0] == 200


def test_150_simultaneous_clients_are_all_answered(srv):
    """The listen backlog was 5: of 150 clients at once, half were reset and the rest waited
    up to 107 s for the kernel's retries. Now they queue for the handlers."""
    n = 150
    go, results = threading.Event(), [(0, 0.0)] * n

    def client(i: int) -> None:
        go.wait()
        start = time.perf_counter()
        try:
            status = http_exchange(srv.port, raw_get(srv.port), timeout=30)[0]
        except OSError as err:
            status = type(err).__name__
        results[i] = (status, time.perf_counter() - start)

    threads = [threading.Thread(target=client, args=(i,)) for i in range(n)]
    for t in threads:
        t.start()
    go.set()
    for t in threads:
        t.join(60)
    statuses = [status for status, _ in results]
    assert statuses == [200] * n, {s: statuses.count(s) for s in set(statuses)}
    latency = sorted(t for _, t in results)
    print(f"{n} clients at once: median {latency[n // 2]:.3f} s, slowest {latency[-1]:.3f} s")


@pytest.fixture
def short_timeouts(monkeypatch):
    """Two handlers and 0.5 s for a request, so that the tests take a second."""
    monkeypatch.setattr(server, "WORKERS", 2)
    monkeypatch.setattr(server._Handler, "timeout", 0.5)
    with ExplorerServer(0) as s:
        yield s


def closed_by_server(sock: socket.socket, wait: float) -> bool:
    """Whether the server closed ``sock`` (end of stream, or reset) within ``wait`` s."""
    if not select.select([sock], [], [], wait)[0]:
        return False
    try:
        return sock.recv(1) == b""
    except ConnectionResetError:
        return True


def test_idle_connections_are_closed_and_do_not_block_a_new_client(short_timeouts):
    """Connections that send nothing (three times the handlers) are closed after the
    request timeout; a client behind them is answered."""
    port = short_timeouts.port
    idle = [socket.create_connection(("127.0.0.1", port)) for _ in range(6)]
    try:
        assert http_exchange(port, raw_get(port), timeout=20)[0] == 200
        assert all(closed_by_server(s, 10) for s in idle)
    finally:
        for s in idle:
            s.close()


def test_a_client_sending_a_byte_at_a_time_is_closed_at_the_deadline(short_timeouts):
    """A slowloris: each byte comes before the read timeout, the request never ends. It is
    closed when the time for the whole request is up (0.5 s here), not after its 40 bytes."""
    port = short_timeouts.port
    with socket.create_connection(("127.0.0.1", port)) as s:
        s.sendall(f"GET / HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\n".encode())
        for _ in range(40):
            if closed_by_server(s, 0.1):
                break
            try:
                s.sendall(b"X")
            except OSError:
                break
        else:
            pytest.fail("the slow request was still open after 4 s")
    assert answers(port)


MALFORMED = {
    "no request line": (b"garbage\r\n\r\n", 400),
    "one word": (b"GET\r\n\r\n", 400),
    "binary": (b"\x00\xff\xfe\r\n\r\n", 400),
    "URL past 64 KiB": (b"GET /" + b"a" * 70000 + b" HTTP/1.1\r\n\r\n", 414),
    "header past 64 KiB": (b"GET / HTTP/1.1\r\nX: " + b"a" * 70000 + b"\r\n\r\n", 431),
    "200 headers": (b"GET / HTTP/1.1\r\n" + b"X: 1\r\n" * 200 + b"\r\n", 431),
    "unknown version": (b"GET / HTTP/9.9\r\nHost: H\r\n\r\n", 505),
    "huge body, bad JSON": (
        b"POST /api/motion HTTP/1.1\r\nHost: H\r\nContent-Length: 1000000000000\r\n\r\n{bad",
        501,
    ),
    "a full URL": (b"GET http://evil.example/ HTTP/1.1\r\nHost: H\r\n\r\n", 400),
    "asterisk": (b"OPTIONS * HTTP/1.1\r\nHost: H\r\n\r\n", 400),
    "dot-dot": (b"GET /../pyproject.toml HTTP/1.1\r\nHost: H\r\n\r\n", 404),
    "encoded dot-dot": (b"GET /%2e%2e/%2e%2e/pyproject.toml HTTP/1.1\r\nHost: H\r\n\r\n", 404),
    "encoded slash in a request": (b"GET /api/..%2f..%2fcli HTTP/1.1\r\nHost: H\r\n\r\n", 404),
    "bad bytes in a query": (b"GET /api/motion?alpha=%ff%00 HTTP/1.1\r\nHost: H\r\n\r\n", 400),
    "long query value": (
        b"GET /api/region?km=" + b"9" * 60000 + b" HTTP/1.1\r\nHost: H\r\n\r\n",
        400,
    ),
    "a query of 5000 fields": (
        b"GET /api/motion?" + b"&".join(b"f%d=1" % i for i in range(5000))
        + b" HTTP/1.1\r\nHost: H\r\n\r\n",
        200,
    ),
}  # fmt: skip


@pytest.mark.parametrize("name", list(MALFORMED))
def test_a_malformed_request_is_a_short_refusal_and_the_server_goes_on(srv, capfd, name):
    request, expected = MALFORMED[name]
    request = request.replace(b"Host: H", f"Host: 127.0.0.1:{srv.port}".encode())
    status, body = http_exchange(srv.port, request)
    assert status == expected, body[:200]
    if status != 200:
        assert len(body) <= 300 and b"Traceback" not in body, body[:300]
    assert answers(srv.port)
    assert "Traceback" not in capfd.readouterr().err


def test_the_page_fetches_nothing_from_the_internet():
    """Every address in the page's files is relative (the SVG namespace is a name, not a
    download)."""
    for name in ("index.html", "explorer.js", "explorer.css"):
        text = server.static_file(name).decode()
        urls = set(re.findall(r"(?:https?:)?//[\w.-]+\.\w+[^\s\"'`)]*", text))
        assert urls <= {"http://www.w3.org/2000/svg"}, (name, urls)
        assert "@import" not in text and '<link rel="preconnect"' not in text


def test_the_static_files_are_in_the_package_directory():
    """maturin ships every file under python/eccjump in the wheel: the page must live there."""
    static = server.resources.files("eccjump.explorer").joinpath("static")
    assert {p.name for p in static.iterdir()} >= {"index.html", "explorer.js", "explorer.css"}


# --- the command line ----------------------------------------------------------------------


def _explore(*args: str) -> subprocess.Popen:
    return subprocess.Popen(
        [sys.executable, "-m", "eccjump.cli", "explore", "--no-browser", *args],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )


@pytest.mark.slow
def test_cli_serves_until_ctrl_c():
    proc = _explore("--port", "0")
    try:
        line = proc.stdout.readline()
        url = re.search(r"http://127\.0\.0\.1:(\d+)/", line)
        assert get(url.group(0) + "api/controls")[0] == 200
        # every handler held by a client that sends nothing, and more waiting
        idle = [socket.create_connection(("127.0.0.1", int(url.group(1)))) for _ in range(30)]
        time.sleep(0.2)
        start = time.perf_counter()
        proc.send_signal(signal.SIGINT)
        code = proc.wait(timeout=30)
        print(f"eccjump explore stopped {time.perf_counter() - start:.2f} s after Ctrl-C")
        err = proc.stderr.read()
        assert code == 0 and "Traceback" not in err and "stopped" in err
        for s in idle:
            s.close()
    finally:
        if proc.poll() is None:
            proc.kill()


@pytest.mark.slow
def test_cli_port_in_use_is_one_line_naming_the_option():
    with socket.socket() as taken:
        taken.bind(("127.0.0.1", 0))
        taken.listen()
        proc = _explore("--port", str(taken.getsockname()[1]))
        _, err = proc.communicate(timeout=60)
    assert proc.returncode == 1 and "--port" in err and "Traceback" not in err
    assert len(err.strip().splitlines()) == 1


def test_cli_port_out_of_range_is_refused():
    from eccjump.cli import main

    with pytest.raises(SystemExit) as exc:
        main(["explore", "--port", "70000"])
    assert exc.value.code == 2


# --- the widget (Python side) --------------------------------------------------------------


@pytest.fixture
def widget_module():
    pytest.importorskip("anywidget", reason="eccjump.explore needs anywidget (eccjump[explore])")
    from eccjump.explorer import widget

    return widget


def test_explore_returns_a_widget_holding_the_start(widget_module):
    w = eccjump.explore(**SLIP_FIRST_KW, mu_k=0.5, rule="normal_force")
    assert float(w.params["alpha"]) == pytest.approx(30.0)
    assert (w.params["chi"], w.params["km"], w.params["mu_k"]) == ("0.5", "0.4", "0.5")
    assert (w.params["rule"], w.params["tie"]) == ("normal_force", "0")
    assert eccjump.explore().params["tie"] == "1"
    assert "export default" in (widget_module.STATIC / "explorer.js").read_text()


def test_widget_answers_the_page_through_its_messages(widget_module, monkeypatch):
    w = eccjump.explore()
    sent: list[dict] = []
    monkeypatch.setattr(w, "send", lambda content, buffers=None: sent.append(content))
    w._answer(w, {"kind": "request", "id": 7, "endpoint": "motion", "query": README}, [])
    w._answer(w, {"kind": "request", "id": 8, "endpoint": "motion", "query": {"km": "0.99"}}, [])
    w._answer(w, {"kind": "something else"}, [])
    assert [m["id"] for m in sent] == [7, 8] and all(m["kind"] == "response" for m in sent)
    assert sent[0]["status"] == 200
    assert sent[0]["body"]["numbers"]["liftoff"]["theta_deg"] == pytest.approx(334.34383792)
    assert sent[1]["status"] == 400 and sent[1]["body"]["error"].startswith("No such body")


def test_widget_answers_the_uncertainty_panel_of_its_map(widget_module, map_files, monkeypatch):
    sent: list[dict] = []
    for w, available in ((eccjump.explore(uncertainty=map_files[0]), True),
                         (eccjump.explore(), False)):  # fmt: skip
        monkeypatch.setattr(w, "send", lambda content, buffers=None: sent.append(content))
        w._answer(w, {"kind": "request", "id": 1, "endpoint": "uncertainty", "query": {}}, [])
        assert sent[-1]["status"] == 200 and sent[-1]["body"]["available"] is available
    with pytest.raises(ValueError, match=r"uncertainty: .* holds a 'jarm' map"):
        eccjump.explore(uncertainty=map_files[1])


@pytest.mark.parametrize(
    ("kwargs", "error", "names"),
    [
        ({"alpha": 2.0}, ValueError, r"alpha = 2 rad .*\[0, 1\.5708\] rad"),
        ({"theta0": -4.0}, ValueError, r"theta0 = -4 rad"),
        ({"chi": 1.5}, ValueError, r"chi = 1\.5 is outside"),
        ({"mu_s": math.nan}, ValueError, "mu_s"),
        ({"t_max": 100.0}, ValueError, r"t_max = 100 √\(R/g\)"),
        ({"km": True}, TypeError, "km"),
        ({"mu_k": "1"}, TypeError, "mu_k"),
        ({"rule": "bogus"}, ValueError, "rule"),
        ({"rule": None}, TypeError, "rule"),
    ],
)
def test_explore_refuses_bad_starts(kwargs, error, names):
    with pytest.raises(error, match=names):
        eccjump.explore(**kwargs)
