"""Drawings shared by several scripts (scripts/plot_sff.py, bench/matrix/plot_paths.py)."""


def decomposition_terms(sff, mu):
    """The terms of the decoupled stress ratio (He et al. 2016, Eq. 27) of an SFF table: fabric
    (2/5) a_c, normal force (2/5) a_n and mobilisation (3/5) mu m (sff::decoupled_terms in C++)."""
    return 0.4 * sff["a_c"], 0.4 * sff["a_n"], 0.6 * mu * sff["m"]


def draw_decomposition(ax, sff, mu, legend=True):
    """q/p against axial strain [%] over the stacked SFF terms (2/5)a_c, (2/5)a_n, (3/5)mu m (all
    about z, so an extension test's terms are negative), with eta_SFF and the decoupled eta."""
    eps = 100 * sff["axial_strain"]
    fabric, force, mobilisation = decomposition_terms(sff, mu)
    labels = ["fabric (2/5) a_c", "normal force (2/5) a_n", "mobilisation (3/5) mu m"]
    ax.stackplot(eps, fabric, force, mobilisation, alpha=0.35, labels=labels)
    ax.plot(eps, sff["eta"], "k-o", ms=3, label="eta, contacts")
    ax.plot(eps, sff["eta_sff"], "r--", label="eta_SFF (full tensor equation)")
    ax.plot(eps, sff["eta_decoupled"], "b-.", label="eta decoupled")
    ax.set_xlabel("axial strain [%]")
    ax.set_ylabel("stress ratio q/p [-]")
    ax.grid(alpha=0.3)
    if legend:
        ax.legend(fontsize=8, loc="best")
