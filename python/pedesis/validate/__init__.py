"""pedesis.validate: a curated physics suite that checks pedesis on the user's machine.

Each case runs the engines through the pedesis CLI with fixed seeds, measures a quantity
with its statistical error, and compares it with an exact result or a published
reference at a tolerance it justifies for its run length (docs/validation.md). ``--quick``
runs shorter versions in under 2 minutes on 2 cores; the full suite takes under 30.

    python3 -m pedesis.validate --quick --out runs/validate
    pedesis validate --quick            # the same, through the CLI
"""
from .cases import (active, active_models, granular, gravity, hard, liquid, sedimentation,
                    shear, thermostats, transport)
from .checks import CaseError, CaseResult, Check

# (name, function, runs in quick mode too); in this order in the table
CASES = (
    ("hard_disk_eos", hard.hard_disk_eos, True),
    ("hard_sphere_eos", hard.hard_sphere_eos, True),
    ("hard_disk_dense", hard.hard_disk_dense, False),
    ("stepped_vs_event", hard.stepped_vs_event, True),
    ("equipartition", granular.equipartition, True),
    ("haff", granular.haff, True),
    ("inelastic_mixture", granular.inelastic_mixture, True),
    ("barometric_gas", gravity.barometric_gas, True),
    ("free_abp", active.free_abp, True),
    ("mips", active.mips, True),
    ("abp_walls", active_models.abp_walls, True),
    ("abp_trap", active_models.abp_trap, True),
    ("chiral_abp", active_models.chiral_abp, True),
    ("run_and_tumble", active_models.run_and_tumble, True),
    ("aoup_msd", active_models.aoup_msd, True),
    ("abp_sedimentation", sedimentation.abp_sedimentation, True),
    ("lennard_jones", liquid.lennard_jones, True),
    ("nvt_thermostats", thermostats.nvt_thermostats, True),
    ("hard_sphere_transport", transport.hard_sphere_transport, True),
    ("dilute_transport", transport.dilute_transport, False),
    ("hard_disk_transport", transport.hard_disk_transport, True),
    ("wca_viscosity", transport.wca_viscosity, True),
    ("hard_sphere_shear", shear.hard_sphere_shear, False),
    ("granular_usf", shear.granular_usf, False),
)

__all__ = ["CASES", "CaseError", "CaseResult", "Check"]
