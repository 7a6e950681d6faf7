"""The listing cache on disk: what is read back is what was built; a file that is
corrupt, truncated, foreign, tampered with or of another format is rebuilt, never
trusted; the directory stays within its limit, oldest first; concurrent writers never
expose a partial file; the directory follows the platform's convention; and the CLI's
``cache info|clear``, ``--no-cache`` and ``RKCHECK_NO_CACHE``."""

from __future__ import annotations

import os
import re
import tempfile
import threading
from pathlib import Path

import numpy as np
import pytest
from support.clirun import run_cli
from trees.test_listing_stream import same_listing

from rkcheck.errors import UserError
from rkcheck.io import cache as cache_module
from rkcheck.io.cache import MAGIC, ListingCache, cache_dir, encode, max_cache_bytes
from rkcheck.numbers.formatting import human_bytes
from rkcheck.trees.listing import ConditionListing, forget_listings, use_store
from rkcheck.trees.stored import record_key, to_record

RK4 = str(Path(__file__).resolve().parents[2] / "tableaux" / "explicit" / "rk4.toml")


@pytest.fixture(autouse=True)
def no_default_store():
    previous = use_store(None)
    yield
    use_store(previous)


@pytest.fixture
def store(tmp_path):
    return ListingCache(tmp_path / "cache", limit=1 << 30, min_terms=0)


def fresh(order=8, degree=None):
    return ConditionListing(order, degree, None).complete()


def test_what_is_read_back_is_what_was_built(store):
    built = ConditionListing(8, None, store).complete()
    assert built.cache_hits == []
    assert len(store.files()) == 7  # 3 … 9 vertices
    read = ConditionListing(8, None, store).complete()
    assert read.cache_hits == list(range(3, 10))
    same_listing(built, read)
    same_listing(fresh(), read)


def test_a_degree_bound_has_files_of_its_own(store):
    ConditionListing(8, None, store).complete()
    read = ConditionListing(8, 3, store).complete()
    assert read.cache_hits == []  # nothing of degree none is taken for degree 3
    same_listing(fresh(8, 3), read)


def _file(store: ListingCache, n: int, degree=None) -> Path:
    return store.path(record_key(n, degree))


def _flip_byte(path: Path, at: int) -> None:
    data = bytearray(path.read_bytes())
    data[at] ^= 0x01
    path.write_bytes(bytes(data))


def _damage_payload(store, path):
    _flip_byte(path, path.stat().st_size - 5)  # inside the last array


def _damage_header(store, path):
    data = path.read_bytes()
    path.write_bytes(data.replace(b'"superfluous":', b'"superfluouz":', 1))


def _truncate(store, path):
    data = path.read_bytes()
    path.write_bytes(data[: len(data) // 2])


def _foreign(store, path):
    # a valid file of another order under this order's name
    path.write_bytes(_file(store, 8).read_bytes())


def _garbage(store, path):
    path.write_bytes(os.urandom(4096))


def _empty(store, path):
    path.write_bytes(b"")


def _other_format(store, path):
    # intact, hash and all, but written by another format of the records
    listing = fresh()
    o = listing.orders[9]
    lo, hi = listing.first[9], listing.first[10]
    key = dict(record_key(9, None), format=99)
    path.write_bytes(b"".join(bytes(p) for p in encode(key, *to_record(listing.left[lo:hi], listing.right[lo:hi], o))))


def _valid_hash_bad_index(store, path):
    # a well-formed file whose hash matches, but a factor points past its order
    listing = fresh()
    o = listing.orders[9]
    lo, hi = listing.first[9], listing.first[10]
    left = listing.left[lo:hi].copy()
    left[3] = lo + 5  # a tree with 9 vertices cannot be a factor of one with 9
    path.write_bytes(b"".join(bytes(p) for p in encode(record_key(9, None), *to_record(left, listing.right[lo:hi], o))))


def _valid_hash_wrong_counts(store, path):
    # well-formed and in range, but a term moved to another condition
    listing = fresh()
    o = listing.orders[9]
    lo, hi = listing.first[9], listing.first[10]
    arrays, meta = to_record(listing.left[lo:hi], listing.right[lo:hi], o)
    arrays = dict(arrays, condition=arrays["condition"].copy())
    i = int(np.flatnonzero(arrays["condition"] != arrays["condition"][0])[0])
    arrays["condition"][i] = arrays["condition"][0]
    path.write_bytes(b"".join(bytes(p) for p in encode(record_key(9, None), arrays, meta)))


def _valid_hash_coefficient(text):
    def damage(store, path):
        # well-formed, hash and all, but a coefficient is no integer int() reads
        listing = fresh()
        o = listing.orders[9]
        lo, hi = listing.first[9], listing.first[10]
        arrays, meta = to_record(listing.left[lo:hi], listing.right[lo:hi], o)
        meta = dict(meta, coefficients=[text, *meta["coefficients"][1:]])
        path.write_bytes(b"".join(bytes(p) for p in encode(record_key(9, None), arrays, meta)))

    damage.__name__ = f"_coefficient_{text.encode('unicode_escape').decode()}"
    return damage


DAMAGE = [_damage_payload, _damage_header, _truncate, _foreign, _garbage, _empty, _other_format,
          _valid_hash_bad_index, _valid_hash_wrong_counts,
          _valid_hash_coefficient("\u00b2"), _valid_hash_coefficient("--1"), _valid_hash_coefficient("\u0663")]


@pytest.mark.parametrize("damage", DAMAGE, ids=lambda f: f.__name__.strip("_"))
def test_a_damaged_file_is_rebuilt_never_trusted(store, damage):
    ConditionListing(8, None, store).complete()
    path = _file(store, 9)
    damage(store, path)
    listing = ConditionListing(8, None, store).complete()
    assert 9 not in listing.cache_hits and listing.cache_hits == list(range(3, 9))
    same_listing(fresh(), listing)
    # rebuilt and saved again: the next run reads it
    assert ConditionListing(8, None, store).complete().cache_hits == list(range(3, 10))


@pytest.mark.parametrize("n", [5, 7])
def test_factors_read_into_the_listing_and_found_damaged_are_rebuilt(store, n):
    # the factors are read in place: a damaged record below the top leaves them to a
    # table grown anew, which must rewrite them (and the orders read before it)
    ConditionListing(8, None, store).complete()
    data = bytearray(_file(store, n).read_bytes())
    head = len(MAGIC) + 8 + int.from_bytes(data[len(MAGIC):len(MAGIC) + 8], "little")
    data[head + 4] ^= 0x40  # the second left factor: the first array after the header
    _file(store, n).write_bytes(bytes(data))
    listing = ConditionListing(8, None, store).complete()
    assert n not in listing.cache_hits
    same_listing(fresh(), listing)


def test_arrays_are_read_into_the_given_ones_when_they_fit(store):
    built = ConditionListing(6, None, store).complete()
    lo, hi = built.first[7], built.first[8]
    into = {"left": np.full(hi - lo, -7, dtype=np.int32), "right": np.full(hi - lo + 1, -7, dtype=np.int32)}
    arrays, _ = store.load(record_key(7, None), into)
    assert arrays["left"] is into["left"]  # filled in place
    assert arrays["right"] is not into["right"]  # another length: an array of its own
    np.testing.assert_array_equal(into["left"], built.left[lo:hi])
    np.testing.assert_array_equal(arrays["right"], built.right[lo:hi])


def test_a_file_is_plain_integers_behind_a_magic_line(store):
    ConditionListing(5, None, store).complete()
    data = _file(store, 6).read_bytes()
    assert data.startswith(MAGIC)
    assert b"pickle" not in data and b"\x80\x04" not in data[: len(MAGIC) + 8]  # no pickle protocol header


def test_the_directory_is_kept_within_its_limit_oldest_first(tmp_path):
    unbounded = ListingCache(tmp_path / "c", limit=1 << 30, min_terms=0)
    ConditionListing(8, None, unbounded).complete()
    files = unbounded.files()
    sizes = {p.name: size for p, size, _ in files}
    # make the files' ages explicit: 3 vertices oldest … 9 newest
    for age, n in enumerate(range(3, 10)):
        os.utime(_file(unbounded, n), (1_000_000 + age, 1_000_000 + age))
    newest_two = sizes[_file(unbounded, 9).name] + sizes[_file(unbounded, 8).name]
    bounded = ListingCache(tmp_path / "c", limit=newest_two, min_terms=0)
    bounded.evict()
    assert sorted(p.name for p, _, _ in bounded.files()) == sorted([_file(unbounded, 8).name, _file(unbounded, 9).name])
    assert bounded.info().bytes <= bounded.limit


def test_reading_a_file_makes_it_the_most_recent(tmp_path):
    store = ListingCache(tmp_path / "c", limit=1 << 30, min_terms=0)
    ConditionListing(5, None, store).complete()
    for age, n in enumerate(range(3, 7)):
        os.utime(_file(store, n), (1_000_000 + age, 1_000_000 + age))
    store.load(record_key(3, None))
    assert store.files()[-1][0] == _file(store, 3)


def test_a_record_larger_than_the_limit_is_not_saved(tmp_path):
    store = ListingCache(tmp_path / "c", limit=100, min_terms=0)
    listing = ConditionListing(8, None, store).complete()
    assert store.files() == [] and len(listing.orders[9]) > 0


def test_an_order_over_the_limit_is_named_and_the_check_says_so(tmp_path):
    # the orders' sizes as the files on disk have them, kept under a limit that holds all
    everything = ListingCache(tmp_path / "all", limit=1 << 30, min_terms=0)
    ConditionListing(7, None, everything).complete()
    sizes = {n: _file(everything, n).stat().st_size for n in range(3, 9)}
    limit = sorted(sizes.values())[3]  # some orders fit, the larger ones do not
    over = sorted(n for n, size in sizes.items() if size > limit)
    assert 0 < len(over) < len(sizes)
    store = ListingCache(tmp_path / "c", limit=limit, min_terms=0)
    listing = ConditionListing(7, None, store).complete()
    assert [int(re.search(r"with (\d+) vertices", note).group(1)) for note in listing.store_notes] == over
    assert all("RKCHECK_MAX_CACHE_BYTES" in note and human_bytes(limit) in note for note in listing.store_notes)
    assert {n for n in sizes if _file(store, n).exists()} <= set(sizes) - set(over)  # the rest may be evicted
    # a check built on such a listing passes the notes on as warnings
    import rkcheck

    use_store(ListingCache(tmp_path / "d", limit=limit, min_terms=0))
    forget_listings()
    try:
        result = rkcheck.verify(RK4, order=7, degree=None)
    finally:
        forget_listings()
    assert [w for w in result.warnings if "listing cache" in w] == listing.store_notes


def test_concurrent_writers_never_expose_a_partial_file(tmp_path):
    store = ListingCache(tmp_path / "c", limit=1 << 30, min_terms=0)
    listing = fresh(9)
    lo, hi = listing.first[10], listing.first[11]
    arrays, meta = to_record(listing.left[lo:hi], listing.right[lo:hi], listing.orders[10])
    key = record_key(10, None)
    seen, stop = [], threading.Event()

    def write():
        for _ in range(15):
            ListingCache(store.directory, store.limit, 0).save(key, arrays, meta)

    def read():
        while not stop.is_set():
            got = store.load(key)
            seen.append(None if got is None else all(np.array_equal(got[0][k], arrays[k]) for k in arrays))

    writers = [threading.Thread(target=write) for _ in range(3)]
    readers = [threading.Thread(target=read) for _ in range(2)]
    for t in readers + writers:
        t.start()
    for t in writers:
        t.join()
    stop.set()
    for t in readers:
        t.join()
    assert False not in seen  # a reader saw nothing yet, or the whole file
    assert True in seen
    assert [p.name for p in store.directory.iterdir()] == [store.path(key).name]  # no temporary file left


def _others(directory: Path) -> list[str]:
    """Files of other programs in the cache directory, some named like rkcheck's."""
    (directory / "notes.txt").write_text("mine")
    (directory / "notes.rkl").write_text("my notes")
    (directory / ".tmp-abc.rkl").write_text("not a name mkstemp gives")
    (directory / "condition-listing-f1-n99-mnone.rkl").write_bytes(b"no magic line")
    names = ["notes.txt", "notes.rkl", ".tmp-abc.rkl", "condition-listing-f1-n99-mnone.rkl"]
    if hasattr(os, "mkfifo"):
        os.mkfifo(directory / "condition-listing-f1-n98-mnone.rkl")
        names.append("condition-listing-f1-n98-mnone.rkl")
    return sorted(names)


def test_clear_removes_listing_files_and_leftovers_only(tmp_path):
    store = ListingCache(tmp_path / "c", limit=1 << 30, min_terms=0)
    ConditionListing(5, None, store).complete()
    fd, _ = tempfile.mkstemp(prefix=".tmp-", suffix=".rkl", dir=store.directory)  # an interrupted save
    os.write(fd, MAGIC[:5])
    os.close(fd)
    others = _others(store.directory)
    assert store.info().files == 4  # 3 to 6 vertices
    assert store.clear() == 4
    assert sorted(p.name for p in store.directory.iterdir()) == others


def test_eviction_removes_listing_files_only(tmp_path):
    store = ListingCache(tmp_path / "c", limit=1 << 30, min_terms=0)
    store.directory.mkdir(parents=True)
    others = _others(store.directory)
    ConditionListing(6, None, store).complete()
    store.limit = 0
    store.evict()
    assert sorted(p.name for p in store.directory.iterdir()) == others


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="named pipes")
def test_a_named_pipe_in_place_of_a_listing_is_passed_over(tmp_path):
    # opened for reading, a pipe waits for a writer: the load would never return
    store = ListingCache(tmp_path / "c", limit=1 << 30, min_terms=0)
    store.directory.mkdir(parents=True)
    os.mkfifo(_file(store, 7))
    done = []
    worker = threading.Thread(target=lambda: done.append(ConditionListing(6, None, store).complete()), daemon=True)
    worker.start()
    worker.join(30)
    assert done, "the load waited on the pipe"
    assert 7 not in done[0].cache_hits
    same_listing(fresh(6), done[0])


# ------------------------------------------------------------------ where


@pytest.mark.parametrize("platform, env, expected", [
    ("linux", {"XDG_CACHE_HOME": "/x/cache"}, "/x/cache/rkcheck"),
    ("linux", {"XDG_CACHE_HOME": "relative/ignored"}, "{home}/.cache/rkcheck"),
    ("linux", {}, "{home}/.cache/rkcheck"),
    ("darwin", {"XDG_CACHE_HOME": "/x/cache"}, "{home}/Library/Caches/rkcheck"),
    ("win32", {"LOCALAPPDATA": "/w/local"}, "/w/local/rkcheck/Cache"),
    ("linux", {"RKCHECK_CACHE_DIR": "/explicit", "XDG_CACHE_HOME": "/x"}, "/explicit"),
])
def test_the_cache_directory_follows_the_platform_convention(monkeypatch, tmp_path, platform, env, expected):
    for name in ("RKCHECK_CACHE_DIR", "XDG_CACHE_HOME", "LOCALAPPDATA"):
        monkeypatch.delenv(name, raising=False)
    for name, value in env.items():
        monkeypatch.setenv(name, value)
    monkeypatch.setenv("HOME", str(tmp_path))
    monkeypatch.setattr(cache_module.sys, "platform", platform)
    assert cache_dir() == Path(expected.format(home=tmp_path))


def test_the_limit_is_named_and_can_be_set(monkeypatch):
    monkeypatch.delenv("RKCHECK_MAX_CACHE_BYTES", raising=False)
    assert max_cache_bytes() == cache_module.MAX_CACHE_BYTES == 2 * 1024**3
    monkeypatch.setenv("RKCHECK_MAX_CACHE_BYTES", "1_000_000")
    assert max_cache_bytes() == 1_000_000
    for bad in ("-1", "1e9", "9" * 26):  # the last: more bytes than any disk, said so
        monkeypatch.setenv("RKCHECK_MAX_CACHE_BYTES", bad)
        with pytest.raises(UserError, match="non-negative number of bytes of at most 20 digits"):
            max_cache_bytes()


# ------------------------------------------------------------------ the CLI


@pytest.fixture
def cli_cache(tmp_path, monkeypatch):
    directory = tmp_path / "user-cache"
    monkeypatch.setenv("RKCHECK_CACHE_DIR", str(directory))
    monkeypatch.delenv("RKCHECK_NO_CACHE", raising=False)
    monkeypatch.delenv("RKCHECK_MAX_CACHE_BYTES", raising=False)
    forget_listings()  # listings built by earlier tests are in memory, not in this cache
    return directory


def _listing_files(directory: Path) -> list[str]:
    return sorted(p.name for p in directory.glob("*.rkl")) if directory.exists() else []


def test_verify_saves_the_large_orders_and_reads_them_back(capsys, cli_cache):
    # order 13: the rooted trees with 14 vertices (32,973) are worth a file, fewer are not
    first = run_cli(capsys, "verify", RK4, "-N", "13", "--format", "json")
    assert first.code == 0, first.err
    assert _listing_files(cli_cache) == ["condition-listing-f1-n14-mnone.rkl"]
    again = run_cli(capsys, "verify", RK4, "-N", "13", "--format", "json")
    assert again.out.split('"timings"')[0] == first.out.split('"timings"')[0]
    info = run_cli(capsys, "cache", "info")
    assert info.code == 0
    assert f"path   {cli_cache}" in info.out and "files  1" in info.out
    size = (cli_cache / "condition-listing-f1-n14-mnone.rkl").stat().st_size
    assert f"({size:,} bytes)" in info.out and "(2,147,483,648 bytes)" in info.out


def test_no_cache_neither_reads_nor_saves(capsys, cli_cache, monkeypatch):
    assert run_cli(capsys, "verify", RK4, "-N", "13", "--no-cache").code == 0
    assert _listing_files(cli_cache) == []
    monkeypatch.setenv("RKCHECK_NO_CACHE", "1")
    assert run_cli(capsys, "verify", RK4, "-N", "13").code == 0
    assert _listing_files(cli_cache) == []


@pytest.mark.parametrize("value, off", [("0", False), ("false", False), (" No ", False), ("OFF", False),
                                        ("1", True), ("yes", True), ("true", True)])
def test_no_cache_in_the_environment_reads_false_as_false(capsys, cli_cache, monkeypatch, value, off):
    monkeypatch.setenv("RKCHECK_NO_CACHE", value)
    assert run_cli(capsys, "verify", RK4, "-N", "13").code == 0
    assert (_listing_files(cli_cache) == []) is off


def test_cache_clear(capsys, cli_cache):
    run_cli(capsys, "verify", RK4, "-N", "13")
    (cli_cache / "keep.txt").write_text("not a listing")
    r = run_cli(capsys, "cache", "clear")
    assert r.code == 0 and r.out.startswith("removed 1 listing file (519.4 KiB) from ") and str(cli_cache) in r.out
    assert sorted(p.name for p in cli_cache.iterdir()) == ["keep.txt"]


def test_a_bad_cache_limit_is_one_line_naming_it(capsys, cli_cache, monkeypatch):
    monkeypatch.setenv("RKCHECK_MAX_CACHE_BYTES", "lots")
    r = run_cli(capsys, "verify", RK4, "-N", "4")
    assert r.code == 2
    assert r.err.strip().count("\n") == 0 and "RKCHECK_MAX_CACHE_BYTES" in r.err


@pytest.mark.parametrize("command", [("verify", RK4, "-N", "13"), ("cache", "info"), ("cache", "clear")])
def test_a_cache_directory_of_no_users_home_is_one_line_naming_it(capsys, cli_cache, monkeypatch, command):
    pwd = pytest.importorskip("pwd")
    user = "rkcheck-no-such-user"
    with pytest.raises(KeyError):
        pwd.getpwnam(user)
    monkeypatch.setenv("RKCHECK_CACHE_DIR", f"~{user}/listings")
    r = run_cli(capsys, *command)
    assert r.code == 2 and r.err.strip().count("\n") == 0
    assert f"RKCHECK_CACHE_DIR: cannot expand '~{user}/listings'" in r.err
    if command[0] == "verify":  # without the cache, nothing to expand
        assert run_cli(capsys, *command, "--no-cache").code in (0, 1)


@pytest.mark.parametrize("command", ["verify", "scan", "conditions"])
def test_the_commands_that_list_conditions_take_no_cache(capsys, command):
    r = run_cli(capsys, command, "--help")
    assert r.code == 0 and "--no-cache" in r.out


def test_scan_saves_the_listing_and_no_cache_does_not(capsys, cli_cache, tmp_path):
    folder = tmp_path / "methods"
    folder.mkdir()
    (folder / "rk4.toml").write_text(Path(RK4).read_text(encoding="utf-8"), encoding="utf-8")
    assert run_cli(capsys, "scan", str(folder), "-N", "13", "--jobs", "1", "--no-cache").code == 0
    assert _listing_files(cli_cache) == []
    forget_listings()
    assert run_cli(capsys, "scan", str(folder), "-N", "13", "--jobs", "1").code == 0
    assert _listing_files(cli_cache) == ["condition-listing-f1-n14-mnone.rkl"]


def test_cache_info_says_where_its_limit_comes_from_and_a_directory_that_is_not_one(capsys, tmp_path, monkeypatch):
    monkeypatch.setenv("RKCHECK_CACHE_DIR", str(tmp_path / "cache"))
    monkeypatch.delenv("RKCHECK_MAX_CACHE_BYTES", raising=False)
    assert "the default; RKCHECK_MAX_CACHE_BYTES changes it" in run_cli(capsys, "cache", "info").out
    monkeypatch.setenv("RKCHECK_MAX_CACHE_BYTES", "1000000")
    assert "(1,000,000 bytes), set by RKCHECK_MAX_CACHE_BYTES" in run_cli(capsys, "cache", "info").out
    plain = tmp_path / "plain"
    plain.write_text("not a directory", encoding="utf-8")
    monkeypatch.setenv("RKCHECK_CACHE_DIR", str(plain))
    info = run_cli(capsys, "cache", "info")
    assert info.code == 0 and f"{plain} is not a directory" in info.out, info.out
    monkeypatch.setenv("RKCHECK_CACHE_DIR", str(plain / "below"))  # a folder inside a file: never made
    info = run_cli(capsys, "cache", "info")
    assert f"{plain} is not a directory" in info.out, info.out
    monkeypatch.setenv("RKCHECK_CACHE_DIR", str(tmp_path / "not-yet" / "made"))  # made on the first save
    assert "is not a directory" not in run_cli(capsys, "cache", "info").out
