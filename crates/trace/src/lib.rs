//! invlight-trace (to be written).
