//! invlight-render (to be written).
