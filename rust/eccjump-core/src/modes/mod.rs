//! The modes of motion, each a constraint on Newton–Euler ([`crate::mechanics`]) with its
//! equations, fast closed forms and events: pure rolling ([`rolling`]), slipping
//! ([`slipping`]; near the Painlevé singularity in the normal impulse, [`slip_in_impulse`])
//! and flight ([`flight`], exact, with the rigorous landing search), and the
//! consistency test that picks the mode of a contact state ([`contact`]).

pub mod contact;
pub mod flight;
pub mod rolling;
pub mod slip_in_impulse;
pub mod slipping;
