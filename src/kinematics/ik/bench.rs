//! The IK benchmark (TRAC-IK protocol), clock supplied by the caller.
