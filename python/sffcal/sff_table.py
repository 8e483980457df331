"""The Markdown table of the SFF results of several runs, one row per test: e0, the peak and last
stress ratio with a_c, a_n, m, the last void ratio, the worst SFF stress error, the worst
|eta_SFF - eta| / |eta| (|eta| > 0.3) and the worst particle-form-vs-wall stress difference. The
peak is the largest |eta|: an extension test's is its most negative stress ratio."""
import numpy as np

from sffcal.runfile import name_of, read_sff


def print_table(paths):
    print("| test | e0 | peak η (ε_a) | a_c, a_n, m at peak | last η (ε_a) | a_c, a_n, m at last | last e | "
          "max ‖σ_SFF−σ‖/‖σ‖ | max \\|η_SFF−η\\|/\\|η\\| | max \\|σ−σ_walls\\|/p |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for path in paths:
        t = read_sff(path)
        magnitude = np.abs(t["eta"])
        k, last = int(np.argmax(magnitude)), len(t["eta"]) - 1
        sheared = magnitude > 0.3
        eta_error = (np.max(np.abs(t["eta_sff"] - t["eta"])[sheared] / magnitude[sheared])
                     if sheared.any() else 0.0)
        wall = np.max(t["wall_stress_error"]) if "wall_stress_error" in t else float("nan")
        print(f"| {name_of(path)} | {t['void_ratio'][0]:.3f} | {t['eta'][k]:.3f} ({100 * t['axial_strain'][k]:.1f} %) | "
              f"{t['a_c'][k]:.2f}, {t['a_n'][k]:.2f}, {t['m'][k]:.2f} | "
              f"{t['eta'][last]:.3f} ({100 * t['axial_strain'][last]:.1f} %) | "
              f"{t['a_c'][last]:.2f}, {t['a_n'][last]:.2f}, {t['m'][last]:.2f} | {t['void_ratio'][last]:.3f} | "
              f"{100 * np.max(t['sff_error']):.1f} % | {100 * eta_error:.1f} % | {100 * wall:.2f} % |")

