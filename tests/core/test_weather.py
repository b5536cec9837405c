"""Weather files from the field: EPW, TMY3 and TMY2 read into one time convention,
illuminance units decided from the data, validation with one clear line each.

Real files: tests/data/weather (see its SOURCES.md) and pvlib's own three. Checked
against independent computations written here: a solar-position formula (NOAA's
general solar position equations), the files' own sums read with pandas, and the
same year written in another format.
"""

from __future__ import annotations

import gzip
import math
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from lightinv_core.climate.transposition import sun_and_sky
from lightinv_core.climate.weather import BUILTIN, WeatherError, read_weather
from lightinv_core.design.model import Daylight
from lightinv_core.light.daylight_year import (
    SkyGroups,
    daylight_year,
    dimming_sum,
    hours_from,
)

pvlib = pytest.importorskip("pvlib")  # the climate extra; ./dev.sh installs it
pd = pytest.importorskip("pandas")

DATA = Path(__file__).resolve().parents[1] / "data" / "weather"
PVLIB = Path(pvlib.__file__).parent / "data"
REAL = [
    *sorted(p.name[:-3] for p in DATA.glob("*.gz")),
    "pvlib:723170TYA.CSV",
    "pvlib:703165TY.csv",
    "pvlib:12839.tm2",
]


@pytest.fixture(scope="session")
def real_dir(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("weather")
    for gz in DATA.glob("*.gz"):
        (out / gz.name[:-3]).write_bytes(gzip.decompress(gz.read_bytes()))
    return out


def real(name: str, real_dir: Path) -> Path:
    return PVLIB / name[6:] if name.startswith("pvlib:") else real_dir / name


# -- independent references -----------------------------------------------------------


def raw_records(path: Path) -> pd.DataFrame:
    """month, day, hour (1-24, hour ending), GHI and DNI as the file writes them, read
    with pandas (or pvlib for TMY2's fixed columns), not with LightInv's readers."""
    head = path.read_bytes()[:200]
    if head.upper().startswith(b"LOCATION"):
        df = pd.read_csv(path, skiprows=8, header=None, encoding="latin-1")
        return pd.DataFrame(
            {"month": df[1], "day": df[2], "hour": df[3], "ghi": df[13], "dni": df[14]}
        )
    if path.suffix.lower() == ".tm2":
        df, _ = pvlib.iotools.read_tmy2(str(path))
        return df[["month", "day", "hour"]].assign(ghi=df["GHI"], dni=df["DNI"])
    df = pd.read_csv(path, skiprows=1, encoding="latin-1")
    md = df.iloc[:, 0].str.split("/", expand=True).astype(int)
    hour = df.iloc[:, 1].str.split(":", expand=True)[0].astype(int)
    return pd.DataFrame(
        {
            "month": md[0],
            "day": md[1],
            "hour": hour,
            "ghi": df["GHI (W/m^2)"],
            "dni": df["DNI (W/m^2)"],
        }
    )


def noaa_elevation(lat, lon, tz, day_of_year, local_hours) -> np.ndarray:
    """Solar elevation (deg, no refraction) from NOAA's general solar position
    equations (Spencer's series; about 0.5 degree accurate)."""
    g = 2 * np.pi / 365 * (day_of_year - 1 + (local_hours - 12) / 24)
    eqtime = 229.18 * (
        0.000075
        + 0.001868 * np.cos(g)
        - 0.032077 * np.sin(g)
        - 0.014615 * np.cos(2 * g)
        - 0.040849 * np.sin(2 * g)
    )
    decl = (
        0.006918
        - 0.399912 * np.cos(g)
        + 0.070257 * np.sin(g)
        - 0.006758 * np.cos(2 * g)
        + 0.000907 * np.sin(2 * g)
        - 0.002697 * np.cos(3 * g)
        + 0.00148 * np.sin(3 * g)
    )
    solar_minutes = local_hours * 60 + eqtime + 4 * lon - 60 * tz
    ha = np.radians(solar_minutes / 4 - 180)
    phi = math.radians(lat)
    cosz = np.sin(phi) * np.sin(decl) + np.cos(phi) * np.cos(decl) * np.cos(ha)
    return 90 - np.degrees(np.arccos(np.clip(cosz, -1, 1)))


# -- real files -----------------------------------------------------------------------


@pytest.mark.parametrize("name", REAL)
def test_a_real_file_gives_the_sun_where_its_direct_light_is(name, real_dir):
    path = real(name, real_dir)
    w = read_weather(path)
    raw = raw_records(path)
    assert w.hours == len(raw) in (8760, 8784)
    # Record by record (the reader sorts only files out of calendar order: none here).
    np.testing.assert_array_equal(
        np.asarray(w.times.month), raw["month"].where(raw["hour"] < 24, np.asarray(w.times.month))
    )
    sky = sun_and_sky(w)
    top = np.argsort(-raw["dni"].to_numpy())[:40]
    doy = pd.to_datetime(
        {
            "year": 2001,
            "month": raw["month"],
            "day": raw["day"].where(~((raw["month"] == 2) & (raw["day"] == 29)), 28),
        }
    ).dt.day_of_year.to_numpy()
    ref = noaa_elevation(
        w.latitude, w.longitude, w.utc_offset_h, doy[top], raw["hour"].to_numpy()[top] - 0.5
    )  # at the middle of the hour each record ends
    ours = 90 - sky.zenith[top]
    assert np.abs(ours - ref).max() < 1.5, (name, np.abs(ours - ref).max())
    assert ref.min() > 5  # the brightest beams come with the sun well up
    # The year's global horizontal irradiation is the file's own sum.
    ghi = raw["ghi"].to_numpy(float)
    assert w.ghi.sum() == pytest.approx(ghi[(ghi >= 0) & (ghi < 9999)].sum(), rel=1e-9)
    assert np.all(np.isfinite(w.gh_lux)) and w.gh_lux.max() < 150_000
    assert 80 < np.median(w.gh_lux[w.ghi > 100] / w.ghi[w.ghi > 100]) < 140
    # No real file gives direct sun at night beyond the threshold, but one whose data
    # has it at any clock (Mannheim's DNI without any global light) and says so.
    hours = raw["hour"].to_numpy(float)
    start = noaa_elevation(w.latitude, w.longitude, w.utc_offset_h, doy, hours - 1)
    end = noaa_elevation(w.latitude, w.longitude, w.utc_offset_h, doy, hours)
    dark = (start < -1) & (end < -1)
    at_night = int(((raw["dni"].to_numpy(float) > 50) & dark).sum())
    assert (at_night <= 10) == (name != "mannheim.epw"), at_night
    deep = (start < -3) & (end < -3)
    assert np.all(w.dni[deep] == 0)  # a beam with the sun down all hour lights nothing
    shifted = [n for n in w.notes if "below the horizon" in n]
    assert bool(shifted) == (name == "mannheim.epw")


def test_epw_records_are_hour_ending(real_dir):
    # EPW hour 1 is 00:00-01:00: LightInv labels it 01:00 and takes the sun at 00:30
    # (pvlib's read_epw labels it 00:00: the sun an hour early, as main did).
    w = read_weather(real_dir / "chicago.epw")
    assert str(w.times[0]) == "1986-01-01 01:00:00-06:00"
    raw = raw_records(real_dir / "chicago.epw")
    occupied = w.occupied(8, 18)
    assert sorted(set(raw["hour"][occupied])) == list(range(9, 19))  # 08:00-18:00 data
    assert w.describe()["time_convention"].startswith("hour ending")


def test_the_same_year_in_another_format_gives_the_same_metrics(tmp_path):
    tmy3 = read_weather(BUILTIN)
    epw = tmp_path / "greensboro.epw"
    write_epw(tmy3, epw)
    again = read_weather(epw)
    assert again.format == "EPW" and tmy3.format == "TMY3"
    for k in ("ghi", "dni", "dhi", "gh_lux", "dn_lux", "dh_lux"):
        np.testing.assert_allclose(getattr(again, k), getattr(tmy3, k), atol=0.5)
    assert (again.times == tmy3.times).all()
    a = metrics(BUILTIN)
    b = metrics(epw)
    for key in a:
        np.testing.assert_allclose(b[key], a[key], atol=0.005, err_msg=key)  # 0.5 points


def write_epw(w, path: Path) -> None:
    """The weather ``w`` as an EPW file (the test's own writer)."""
    lines = [
        f"LOCATION,{w.name.split(',')[0]},NC,USA,TMY3,723170,{w.latitude},{w.longitude},"
        f"{w.utc_offset_h},{w.altitude}",
        "DESIGN CONDITIONS,0",
        "TYPICAL/EXTREME PERIODS,0",
        "GROUND TEMPERATURES,0",
        "HOLIDAYS/DAYLIGHT SAVINGS,No,0,0,0",
        "COMMENTS 1,written by tests/core/test_weather.py",
        "COMMENTS 2,",
        "DATA PERIODS,1,1,Data,Sunday, 1/ 1,12/31",
    ]
    mid = w.midpoints
    for i in range(w.hours):
        fields = [mid[i].year, mid[i].month, mid[i].day, mid[i].hour + 1, 60, "?", 20, 10, 50]
        fields += [101325, 0, 0, 300, round(w.ghi[i]), round(w.dni[i]), round(w.dhi[i])]
        fields += [round(w.gh_lux[i]), round(w.dn_lux[i]), round(w.dh_lux[i]), 0]
        fields += [0] * 15
        lines.append(",".join(str(f) for f in fields))
    path.write_text("\n".join(lines) + "\n")


def metrics(path: Path) -> dict[str, np.ndarray]:
    """DA300, UDI 100-3000 and dimming under a rooflight for receivers of 0.5-10%
    daylight factor, through the optimiser's own daylight year."""
    groups = SkyGroups((("roof",),), np.array([[0.0, 0.0, 1.0]]), (np.arange(1),), np.ones(1))
    year = daylight_year(groups, Daylight(weather=str(path)))
    a = np.linspace(0.005, 0.1, 20)[:, None]
    T = year.hours
    levels = dimming_sum(year, a, np.full(len(a), 400.0), 500.0, 0.1) / T
    udi = (hours_from(year, a, 100.0) - hours_from(year, a, 3000.0)) / T
    return {"da300": hours_from(year, a, 300.0) / T, "udi": udi, "dimming": levels}


def test_tmy3_illuminance_units_come_from_the_data(real_dir):
    # pvlib's Sand Point file is in lux already; Greensboro's in hundreds of lux.
    lux = read_weather(PVLIB / "703165TY.csv")
    assert lux.illuminance.startswith("lux") and lux.gh_lux.max() < 120_000
    hundreds = read_weather(BUILTIN)
    assert hundreds.illuminance.startswith("hundreds of lux") and hundreds.gh_lux.max() > 50_000
    # An EPW written in TMY2's raw units (New Delhi, from the ASHRAE 140 drivers).
    delhi = read_weather(real_dir / "421810.epw")
    assert delhi.illuminance.startswith("hundreds of lux")


def test_missing_illuminance_is_modelled_close_to_the_nsrdb_columns(tmp_path):
    # The NSRDB made the TMY3 illuminance with the same Perez 1990 model: blank the
    # columns and the model must give them back.
    text = BUILTIN.read_text().splitlines()
    names = text[1].split(",")
    cols = [names.index(n) for n in ("GH illum (lx)", "DN illum (lx)", "DH illum (lx)")]
    rows = []
    for line in text[2:]:
        f = line.split(",")
        for c in cols:
            f[c] = "0"
        rows.append(",".join(f))
    path = tmp_path / "blank.csv"
    path.write_text("\n".join(text[:2] + rows) + "\n")
    model, file = read_weather(path), read_weather(BUILTIN)
    assert model.illuminance.startswith("modelled")
    for k, tol in (("gh_lux", 0.03), ("dn_lux", 0.05), ("dh_lux", 0.10)):
        assert getattr(model, k).sum() == pytest.approx(getattr(file, k).sum(), rel=tol), k


def test_encodings_leap_years_and_mixed_years(real_dir, tmp_path):
    german = read_weather(real_dir / "mannheim.epw")  # Latin-1 'ü' in a comment line
    assert "read as latin-1 text" in german.notes and german.name.startswith("Mannheim")
    leap = read_weather(real_dir / "SRRL_2012AMY_60min.epw")
    assert leap.hours == 8784 and leap.illuminance.startswith("modelled")
    assert ((leap.times.month == 2) & (leap.times.day == 29)).sum() == 24
    mixed = read_weather(real_dir / "tmy_45.000_8.000_2005_2023.epw")  # PVGIS: years vary
    assert len(set(mixed.midpoints.year)) > 3 and mixed.hours == 8760
    raw = (real_dir / "chicago.epw").read_bytes()
    for codec, data in {
        "utf-8-sig": b"\xef\xbb\xbf" + raw,
        "utf-16": raw.decode("latin-1").encode("utf-16"),
        "cp1252": raw.replace(b"Chicago Ohare", "Chicago Ohare \u00fc".encode("cp1252")),
    }.items():
        p = tmp_path / f"{codec}.epw"
        p.write_bytes(data)
        assert read_weather(p).ghi.sum() == pytest.approx(
            read_weather(real_dir / "chicago.epw").ghi.sum()
        )
    quoted = raw.replace(b"LOCATION,Chicago Ohare Intl Ap", b'LOCATION,"VAN-NUYS-AP"')
    (tmp_path / "q.epw").write_bytes(quoted)
    assert read_weather(tmp_path / "q.epw").name.startswith("VAN-NUYS-AP,")


def test_tmy2_is_read(real_dir):
    miami = read_weather(PVLIB / "12839.tm2")
    assert miami.format == "TMY2" and miami.hours == 8760 and miami.name == "MIAMI"
    assert miami.illuminance.startswith("hundreds of lux")


# -- broken years, one clear line each ------------------------------------------------


def tmy3_lines() -> list[str]:
    return BUILTIN.read_text().splitlines()


def refused(tmp_path, lines_or_text, name="w.csv") -> str:
    p = tmp_path / name
    text = lines_or_text if isinstance(lines_or_text, str) else "\n".join(lines_or_text) + "\n"
    p.write_text(text, encoding="latin-1")
    with pytest.raises(WeatherError) as info:
        read_weather(p)
    msg = str(info.value)
    assert "\n" not in msg and msg.startswith(name)
    return msg


def test_partial_repeated_and_cut_years_are_refused(tmp_path):
    lines = tmy3_lines()
    half = refused(tmp_path, lines[: 2 + 4380])
    assert "4380 hourly records where a year has 8760: 4380 hours are missing" in half
    twice = refused(tmp_path, lines + lines[2 : 2 + 744])
    assert "744 records repeat an hour already given (first: line 8763" in twice
    text = "\n".join(lines)
    cut = refused(tmp_path, text[: int(0.6 * len(text))])
    assert "the file may be cut short" in cut or "is not a number" in cut or "missing" in cut


def test_bad_numbers_are_refused_or_filled_and_said(tmp_path):
    lines = tmy3_lines()
    row = 2 + 24 * 170 + 12  # a June noon
    f = lines[row].split(",")
    f[4] = "abc"
    assert "line 4095: GHI (W/m^2) 'abc' is not a number" in refused(
        tmp_path, [*lines[:row], ",".join(f), *lines[row + 1 :]]
    )
    f[4] = "1e9"
    assert "GHI 1e+09 W/m² is beyond any sunlight" in refused(
        tmp_path, [*lines[:row], ",".join(f), *lines[row + 1 :]]
    )
    f[4] = "NaN"
    p = tmp_path / "gap.csv"
    p.write_text("\n".join([*lines[:row], ",".join(f), *lines[row + 1 :]]) + "\n")
    w = read_weather(p)
    assert "GHI was missing in 1 daylight hours: filled from the neighbouring hours" in w.notes
    assert np.isfinite(w.ghi).all() and w.ghi[row - 2] > 0
    many = list(lines)
    for r in range(2 + 12, len(lines), 24):  # every noon
        g = many[r].split(",")
        g[4] = ""
        many[r] = ",".join(g)
    assert "GHI is missing in 365 daylight hours" in refused(tmp_path, many)


def test_site_and_clock_checks(tmp_path, real_dir):
    lines = tmy3_lines()
    head = lines[0].split(",")
    bad_lat = [",".join([*head[:4], "136.1", *head[5:]]), *lines[1:]]
    assert "latitude 136.1 is not within -90 to 90" in refused(tmp_path, bad_lat)
    far = [",".join([*head[:3], "+3.0", *head[4:]]), *lines[1:]]
    p = tmp_path / "far.csv"
    p.write_text("\n".join(far) + "\n")
    notes = read_weather(p).notes
    assert any("from the solar time of longitude -79.95" in n for n in notes)
    assert any(
        "below the horizon" in n and "every record 8 h later than its time" in n for n in notes
    )
    # Chicago's data moved an hour late against its stamps: the reader finds the hour.
    raw = (real_dir / "chicago.epw").read_text().splitlines()
    head, rows = raw[:8], raw[8:]
    vals = [r.split(",")[6:] for r in rows]
    moved = [",".join(r.split(",")[:6] + vals[i - 1]) for i, r in enumerate(rows)]
    p = tmp_path / "late.epw"
    p.write_text("\n".join(head + moved) + "\n")
    note = [n for n in read_weather(p).notes if "below the horizon" in n]
    assert note and "every record 1 h earlier than its time stamp" in note[0]


def test_json_describes_the_decisions():
    d = read_weather(BUILTIN).describe()
    assert d["format"] == "TMY3" and d["hours"] == 8760 and d["notes"] == []
    assert d["annual_ghi_kwh_m2"] == pytest.approx(1566.2, abs=0.1)
    assert "hundreds of lux" in d["illuminance"]


# -- fuzz: one clear error or a correct year, never a traceback or a partial year ----------

_BASE = BUILTIN.read_bytes()
_EDITS = st.sampled_from(
    ["truncate", "shuffle", "duplicate", "drop", "field", "encode", "header", "swap"]
)


def _mutate(data: bytes, edit: str, r: st.DataObject) -> bytes:
    lines = data.split(b"\n")
    body = range(2, len(lines) - 1)
    if edit == "truncate":
        return data[: r.draw(st.integers(0, len(data) - 1))]
    if edit == "shuffle":  # a full year in another order
        rows = lines[2:-1]
        order = np.random.default_rng(r.draw(st.integers(0, 99))).permutation(len(rows))
        return b"\n".join(lines[:2] + [rows[i] for i in order] + [b""])
    if edit in ("duplicate", "drop"):
        i = r.draw(st.sampled_from(body))
        return b"\n".join(
            lines[: i + 1] + ([lines[i]] if edit == "duplicate" else []) + lines[i + 1 :]
        )
    if edit == "swap":  # two records trade places: still a whole year
        i, j = r.draw(st.sampled_from(body)), r.draw(st.sampled_from(body))
        lines[i], lines[j] = lines[j], lines[i]
        return b"\n".join(lines)
    if edit == "encode":
        codec = r.draw(st.sampled_from(["utf-16", "utf-16-le", "utf-16-be", "utf-8-sig", "cp1252"]))
        return data.decode("latin-1").encode(codec)
    junk = r.draw(
        st.sampled_from(
            ["", "nan", "inf", "-1e308", "1e300", "abc", "-9900", "0x1F", "\u00e9", "1,5"]
        )
    )
    row = 0 if edit == "header" else r.draw(st.sampled_from(body))
    f = lines[row].split(b",")
    f[r.draw(st.integers(0, len(f) - 1))] = junk.encode("utf-8")
    lines[row] = b",".join(f)
    return b"\n".join(lines)


@settings(
    max_examples=25, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture]
)
@given(edit=_EDITS, r=st.data())
def test_fuzzed_weather_files(tmp_path, edit, r):
    path = tmp_path / "fuzz.csv"
    path.write_bytes(_mutate(_BASE, edit, r))
    try:
        w = read_weather(path)
    except WeatherError as exc:
        msg = str(exc)
        assert msg and "\n" not in msg and "Traceback" not in msg
        return
    assert w.hours in (8760, 8784)
    for k in ("ghi", "dni", "dhi", "gh_lux", "dn_lux", "dh_lux"):
        v = getattr(w, k)
        assert np.all(np.isfinite(v)) and np.all(v >= 0), k
    assert w.gh_lux.max() <= 250_000 and w.ghi.max() <= 1500
    # A whole year in another order is the same year.
    if edit in ("shuffle", "swap") and any("calendar order" in n for n in w.notes):
        base = read_weather(BUILTIN)
        np.testing.assert_array_equal(w.ghi, base.ghi)
