//! The project's seeded random generator. TO BE WRITTEN (helper: waves).
